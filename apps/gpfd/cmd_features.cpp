// `gpfd features show|export FILE`: prints a features file, or exports it as code.
#include <fmt/format.h>

#include <filesystem>

#include "command.hpp"
#include "gpfd/expr/export.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/run/checkpoint.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::app {
namespace {

struct FeaturesOptions {
  std::string file;
  std::string format = "infix";
  bool simplify = false;
  std::string out;     // export only: a file instead of stdout.
  bool front = false;  // show only: the run's complexity front.
};

// A run directory stands for its best.features; --front prints its validated front instead.
int showFront(const std::string& dir) {
  if (!std::filesystem::is_directory(dir)) {
    throw InputError("--front needs a run's results directory, not a file", dir);
  }
  const std::string path = dir + "/checkpoint.json";
  if (!std::filesystem::exists(path)) throw InputError("no checkpoint.json: not a run", dir);
  const auto checkpoint = run::parseCheckpoint(readFile(path), path);
  if (checkpoint.validation.sets.empty()) {
    throw InputError("the run has no validated sets (validation.candidates = 0, or unfinished)",
                     dir);
  }
  const auto config = run::parseExperimentConfig(checkpoint.config, path + " (config)");
  const auto names = run::LearningTask(config, run::LearningTask::Budget::Trial).stateNames();
  fmt::print("{}", run::formatFrontTable(checkpoint.validation.sets, names));
  return 0;
}

int run(const FeaturesOptions& o) {
  if (o.front) return showFront(o.file);
  auto file = expr::readFeaturesFile(
      std::filesystem::is_directory(o.file) ? o.file + "/best.features" : o.file);
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
  cmd->add_option("file", o->file, "Features file, or a run's directory (its best.features)")
      ->required();
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
      showCmd->add_flag("--front", show->front,
                        "Print a run's complexity front: the best validated set at each size");
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
