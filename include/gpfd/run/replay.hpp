// run: a finished run read back to be replayed (`gpfd evolve --replay DIR`,
// `gpfd.evolve(replay=DIR)`). A run sized by a time budget takes its population, generations and
// validation sizes from the clock (run/time_budget.hpp) and its learner's settings from a choice
// on the task (run/learner_choice.hpp); its config.toml holds what they came to (the generations
// as fitted to the deadline) and its run.json what was measured and chosen. A replay starts a
// fresh run with exactly those: the same files, byte for byte but timings, on any number of
// threads or workers.
#pragma once

#include <string>

#include "gpfd/run/experiment_config.hpp"

namespace gpfd::run {

struct ReplaySource {
  ExperimentConfig config;  // The run's resolved config, with the generations it made.
  // run.json's "learner_choice", "time_budget" and "env" as they were (JSON; empty: none).
  std::string learnerChoiceJson, timeBudgetJson, envJson;
  bool sizesFromClock = false;  // Whether the run's sizes came from a time budget.
};

// The finished run in `dir`, checked and read. InputError naming `dir` where it is missing, not a
// run's directory, a set of runs (each run-NN is replayed on its own), not finished (resume it
// first), or written by another version of gpfd (`version`), whose runs may differ.
ReplaySource readFinishedRun(const std::string& dir, const std::string& version);

}  // namespace gpfd::run
