// `gpfd features show|export FILE`: prints a features file, or exports it as code.
#include <fmt/format.h>

#include "command.hpp"
#include "gpfd/expr/export.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/util/atomic_file.hpp"

namespace gpfd::app {
namespace {

struct FeaturesOptions {
  std::string file;
  std::string format = "infix";
  bool simplify = false;
  std::string out;  // export only: a file instead of stdout.
};

int run(const FeaturesOptions& o) {
  auto file = expr::readFeaturesFile(o.file);
  if (o.simplify) file.genome = expr::simplify(file.genome);
  const std::string text = expr::exportAs(file.genome, file.variables, o.format);
  if (o.out.empty()) {
    fmt::print("{}", text);
  } else {
    writeFileAtomically(o.out, text);
  }
  return 0;
}

CLI::App* addCommand(CLI::App& parent, const char* name, const char* help,
                     std::vector<std::string> formats, std::shared_ptr<FeaturesOptions> o) {
  auto* cmd = parent.add_subcommand(name, help);
  cmd->add_option("file", o->file, "Features file")->required();
  std::string list;
  for (const auto& f : formats) list += (list.empty() ? "" : "|") + f;
  cmd->add_option("--format", o->format, list)
      ->check(CLI::IsMember(formats))
      ->capture_default_str();
  cmd->add_flag("--simplify", o->simplify, "Simplify algebraically first (values unchanged)");
  return cmd;
}

const CommandRegistration registration{
    "features", [](CLI::App& app) {
      auto* cmd = app.add_subcommand("features", "Print and export features files");
      cmd->require_subcommand(1);
      auto show = std::make_shared<FeaturesOptions>();
      auto* showCmd = addCommand(*cmd, "show", "Print the features of a features file",
                                 {"infix", "sexpr"}, show);
      auto exported = std::make_shared<FeaturesOptions>();
      auto* exportCmd =
          addCommand(*cmd, "export", "Export features as infix, S-expressions, C, NumPy or LaTeX",
                     {"infix", "sexpr", "c", "python", "latex"}, exported);
      exportCmd->add_option("--out", exported->out, "Write to this file instead of stdout");
      return [show, exported, showCmd, exportCmd] {
        return run(showCmd->parsed() ? *show : *exported);
      };
    }};

}  // namespace
}  // namespace gpfd::app
