// `gpfd features show FILE`: prints a features file.
#include <fmt/format.h>

#include "command.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/simplify.hpp"

namespace gpfd::app {
namespace {

struct ShowOptions {
  std::string file;
  std::string format = "infix";
  bool simplify = false;
};

int show(const ShowOptions& o) {
  auto file = expr::readFeaturesFile(o.file);
  const auto format = expr::parseTextFormat(o.format);
  if (o.simplify) file.genome = expr::simplify(file.genome);
  for (std::size_t k = 0; k < file.genome.featureCount(); ++k) {
    const auto tree = file.genome.feature(k);
    fmt::print("{}\n", format == expr::TextFormat::Infix ? expr::toInfix(tree, file.variables)
                                                         : expr::toSexpr(tree, file.variables));
  }
  return 0;
}

const CommandRegistration registration{
    "features", [](CLI::App& app) {
      auto* cmd = app.add_subcommand("features", "Read, print and export features files");
      cmd->require_subcommand(1);
      auto* showCmd = cmd->add_subcommand("show", "Print the features of a features file");
      auto o = std::make_shared<ShowOptions>();
      showCmd->add_option("file", o->file, "Features file")->required();
      showCmd->add_option("--format", o->format, "infix or sexpr")
          ->check(CLI::IsMember({"infix", "sexpr"}))
          ->capture_default_str();
      showCmd->add_flag("--simplify", o->simplify, "Simplify algebraically before printing");
      return [o] { return show(*o); };
    }};

}  // namespace
}  // namespace gpfd::app
