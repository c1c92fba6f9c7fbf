// `gpfd features show|export|eval FILE`: prints a features file, exports it as code, or prints
// its feature values at given states.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <utility>

#include "command.hpp"
#include "gpfd/env/simulate.hpp"
#include "gpfd/expr/export.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/run/checkpoint.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/run_set.hpp"
#include "gpfd/run/stored_config.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"

namespace gpfd::app {
namespace {

struct FeaturesOptions {
  std::string file;
  std::string format = "infix";
  bool simplify = false;
  std::string out;     // export only: a file instead of stdout.
  bool front = false;  // show only: the run's complexity front.
};

// A features file, or a run's results directory standing for its best.features.
std::string featuresPath(const std::string& given) {
  if (!std::filesystem::is_directory(given)) return given;
  if (std::filesystem::exists(given + "/runs.json")) {
    throw InputError(
        "a set of runs: give one run's directory in it (run-01, ...), or --front for every run's "
        "front",
        given);
  }
  if (!std::filesystem::exists(given + "/best.features")) {
    throw InputError(
        "a directory without best.features: give a features file or a run's results directory",
        given);
  }
  return given + "/best.features";
}

struct EvalOptions {
  std::string file;
  std::string state;   // v1,v2,...
  std::string states;  // A CSV file (or - for stdin) with a header naming the variables.
};

std::vector<std::string> splitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1) {
    fields.push_back(line.substr(start, comma - start));
  }
  fields.push_back(line.substr(start));
  for (auto& f : fields) {
    const auto begin = f.find_first_not_of(" \t\r");
    f = begin == std::string::npos ? "" : f.substr(begin, f.find_last_not_of(" \t\r") - begin + 1);
  }
  return fields;
}

// The states of a CSV whose header names (at least) the features file's variables, in any order;
// other columns (a `gpfd simulate` trajectory's step, action, reward) are ignored.
std::vector<std::vector<double>> readStates(std::istream& in, const std::string& source,
                                            const expr::VariableNames& variables) {
  std::string line;
  if (!std::getline(in, line)) throw InputError("empty: no header line", source);
  const auto header = splitFields(line);
  std::vector<std::size_t> column;
  for (const auto& name : variables) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) {
      throw InputError(fmt::format("the header has no column '{}' (the features file's variables: "
                                   "{})",
                                   name, fmt::join(variables, ", ")),
                       source + ":1");
    }
    column.push_back(static_cast<std::size_t>(it - header.begin()));
  }
  std::vector<std::vector<double>> states;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = splitFields(line);
    std::vector<double> state;
    for (std::size_t i = 0; i < column.size(); ++i) {
      const std::string where = fmt::format("{}:{} column {}", source, number, variables[i]);
      if (column[i] >= fields.size()) throw InputError("the row is too short", where);
      state.push_back(parseNumber(fields[column[i]], where));
    }
    states.push_back(std::move(state));
  }
  return states;
}

// CSV: a header f1,...,fK, then the features' values at each state, as the JIT computes them
// (shortest round-trip text, so the numbers read back bit for bit).
int evaluate(const EvalOptions& o) {
  if (o.state.empty() == o.states.empty()) {
    throw InputError("give either --state v1,v2,... or --states FILE", "gpfd features eval");
  }
  const auto file = expr::readFeaturesFile(featuresPath(o.file));
  const std::size_t dim = file.variables.size();
  std::vector<std::vector<double>> states;
  if (!o.state.empty()) {
    states.push_back(env::parseNumberList(o.state, "--state"));
    if (states[0].size() != dim) {
      throw InputError(fmt::format("{} values for the {} variables ({})", states[0].size(), dim,
                                   fmt::join(file.variables, ", ")),
                       "--state");
    }
  } else if (o.states == "-") {
    states = readStates(std::cin, "stdin", file.variables);
  } else {
    if (std::filesystem::is_directory(o.states)) {
      throw InputError("a directory, not a file", o.states);
    }
    std::ifstream in(o.states);
    if (!in) throw InputError("cannot read the states file", o.states);
    states = readStates(in, o.states, file.variables);
  }
  std::unique_ptr<jit::CompiledFeatureMap> map;
  try {
    map = std::make_unique<jit::CompiledFeatureMap>(file.genome, dim);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what(), o.file);
  }
  std::string out;
  for (std::size_t k = 0; k < map->outputDim(); ++k)
    out += fmt::format("{}f{}", k ? "," : "", k + 1);
  out += "\n";
  std::vector<double> features(map->outputDim());
  for (const auto& state : states) {
    map->evaluate(state.data(), features.data());
    out += fmt::format("{}\n", fmt::join(features, ","));
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return 0;
}

constexpr const char* kNoValidatedSets =
    "no validated sets (validation.candidates = 0, or unfinished)";

// The features file of the run in `dir` that names its state variables: best.features, else the
// last generation's best/generation-NNNN.features; empty when it has written neither.
std::string namingFeaturesFile(const std::string& dir) {
  namespace fs = std::filesystem;
  if (fs::exists(dir + "/best.features")) return dir + "/best.features";
  std::string last;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir + "/best", ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("generation-") || !name.ends_with(".features")) continue;
    // generation-0009 before generation-0010 before generation-10000.
    const std::string lastName = fs::path(last).filename().string();
    if (last.empty() || std::pair(name.size(), name) > std::pair(lastName.size(), lastName)) {
      last = entry.path().string();
    }
  }
  return last;
}

// The front table of the run in `dir` (which must hold its checkpoint.json); empty when the run
// has no validated sets. The state variables' names come from the run's features files, so that
// a run on an environment this program cannot make (one stepped in Python by gpfd.evolve, a
// plug-in's) shows its front as it is, nothing re-evaluated.
std::string frontTable(const std::string& dir) {
  const std::string path = dir + "/checkpoint.json";
  if (!std::filesystem::exists(path)) throw InputError("no checkpoint.json: not a run", dir);
  const auto checkpoint = run::parseCheckpoint(readFile(path), path);
  if (checkpoint.validation.sets.empty()) return {};
  const std::string named = namingFeaturesFile(dir);
  if (!named.empty()) {
    return run::formatFrontTable(checkpoint.validation.sets,
                                 expr::readFeaturesFile(named).variables);
  }
  const auto config = run::parseStoredExperimentConfig(checkpoint.config, path + " (config)");
  const auto names = run::LearningTask(config, run::LearningTask::Budget::Trial).stateNames();
  return run::formatFrontTable(checkpoint.validation.sets, names);
}

// A set of runs (`gpfd evolve --runs N`): every run's front, in run order, each under a heading
// naming the run and its seed; a run without a front says why. InputError when no run has one.
std::string setFronts(const std::string& dir) {
  const std::string runsJson = dir + "/runs.json";
  std::uint64_t seed = 0;
  int runs = 0;
  run::parseRunsJson(readFile(runsJson), runsJson, seed, runs);
  std::string text;
  bool anyFront = false;
  for (int r = 1; r <= runs; ++r) {
    const std::string name = run::runDirName(r, runs);
    text += fmt::format("{}{} (seed {})\n", r > 1 ? "\n" : "", name, run::runSeed(seed, r));
    const std::string runDir = dir + "/" + name;
    if (!std::filesystem::exists(runDir + "/checkpoint.json")) {
      text += "no checkpoint yet: not started\n";
      continue;
    }
    const std::string table = frontTable(runDir);
    text += table.empty() ? std::string(kNoValidatedSets) + "\n" : table;
    anyFront = anyFront || !table.empty();
  }
  if (!anyFront) throw InputError(fmt::format("no run of the set has {}", kNoValidatedSets), dir);
  return text;
}

// --front: a run's validated front, or every run's for a set of runs.
int showFront(const std::string& dir) {
  if (!std::filesystem::exists(dir)) throw InputError("no such run directory", dir);
  if (!std::filesystem::is_directory(dir)) {
    throw InputError("--front needs a run's (or a set of runs') results directory, not a file",
                     dir);
  }
  if (std::filesystem::exists(dir + "/runs.json")) {
    fmt::print("{}", setFronts(dir));
    return 0;
  }
  const std::string table = frontTable(dir);
  if (table.empty()) throw InputError(std::string("the run has ") + kNoValidatedSets, dir);
  fmt::print("{}", table);
  return 0;
}

int run(const FeaturesOptions& o) {
  if (o.front) return showFront(o.file);
  auto file = expr::readFeaturesFile(featuresPath(o.file));
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
  cmd->add_option("--format", o->format, list)->check(oneOf(formats))->capture_default_str();
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
                        "Print a run's complexity front: the best validated set at each size "
                        "(every run's, for a set of runs)");
      auto exported = std::make_shared<FeaturesOptions>();
      auto* exportCmd =
          addCommand(*cmd, "export", "Export features as infix, S-expressions, C, NumPy or LaTeX",
                     {"infix", "sexpr", "c", "python", "latex"}, exported);
      exportCmd->add_option("--out", exported->out, "Write to this file instead of stdout");
      auto eval = std::make_shared<EvalOptions>();
      auto* evalCmd = cmd->add_subcommand(
          "eval", "Print the feature values (as the JIT computes them) at given states, as CSV");
      evalCmd->add_option("file", eval->file, "Features file, or a run's directory")->required();
      evalCmd->add_option("--state", eval->state, "One state: v1,v2,...");
      evalCmd->add_option("--states", eval->states,
                          "CSV file (- for stdin) whose header names the variables, e.g. the "
                          "output of gpfd simulate; other columns are ignored");
      return [show, exported, eval, showCmd, evalCmd] {
        if (evalCmd->parsed()) return evaluate(*eval);
        return run(showCmd->parsed() ? *show : *exported);
      };
    }};

}  // namespace
}  // namespace gpfd::app
