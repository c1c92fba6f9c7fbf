#include "gpfd/run/replay.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "gpfd/run/checkpoint.hpp"
#include "gpfd/run/stored_config.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {
namespace fs = std::filesystem;

ReplaySource readFinishedRun(const std::string& dir, const std::string& version) {
  const std::string where = "replay " + dir;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError("no such results directory", where);
  if (fs::exists(dir + "/runs.json")) {
    throw InputError("a set of runs: replay each of its runs (its run-NN directories) on its own",
                     where);
  }
  const std::string checkpointPath = dir + "/checkpoint.json";
  const std::string runPath = dir + "/run.json";
  if (!fs::exists(checkpointPath) || !fs::exists(runPath)) {
    throw InputError(
        "not a run's results directory (it has no checkpoint.json and run.json), or a run that "
        "ended before its first generation",
        where);
  }
  const Checkpoint checkpoint = parseCheckpoint(readFile(checkpointPath), checkpointPath);
  if (checkpoint.version != version) {
    throw InputError("the run was made by gpfd " + checkpoint.version + ", this is " + version +
                         ": another version may make another run from the same sizes",
                     where);
  }
  ReplaySource source;
  source.config = parseStoredExperimentConfig(checkpoint.config, checkpointPath + " (config)");
  const int made = checkpoint.state.generation + 1;
  const bool validated = source.config.validation.candidates == 0 ||
                         checkpoint.validation.finalGeneration == checkpoint.state.generation;
  if (made < source.config.gp.generations || !validated) {
    const std::string stopped = made < source.config.gp.generations
                                    ? "generation " + std::to_string(checkpoint.state.generation) +
                                          " of " + std::to_string(source.config.gp.generations)
                                    : "its validation not done";
    throw InputError("not a finished run (" + stopped +
                         "): finish it with --resume (gpfd.evolve(resume=...)) first",
                     where);
  }
  // A run extended on resume (--generations) made more than its stored config says.
  source.config.gp.generations = made;
  nlohmann::ordered_json run;
  try {
    run = nlohmann::ordered_json::parse(readFile(runPath));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(std::string("run.json is not valid JSON: ") + e.what(), runPath);
  }
  const auto text = [&](const char* key) {
    return run.contains(key) ? run[key].dump() : std::string();
  };
  source.learnerChoiceJson = text("learner_choice");
  source.timeBudgetJson = text("time_budget");
  source.envJson = text("env");
  source.sizesFromClock = !source.timeBudgetJson.empty();
  return source;
}

}  // namespace gpfd::run
