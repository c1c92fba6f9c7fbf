// service: the paper's test protocol as one request (`gpfd assess`, Python's gpfd.assess): the
// config and budget resolved, the feature sets read and checked, every set trained with the long
// budget over N runs, the statistics computed and, when asked, written.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpfd/run/assessment.hpp"
#include "gpfd/run/trial_runner.hpp"
#include "gpfd/service/evolve_text.hpp"
#include "gpfd/service/feature_source.hpp"
#include "gpfd/service/results_directory.hpp"

namespace gpfd::service {

struct AssessRequest {
  std::string env;     // Optional with a config (then it must match).
  std::string config;  // A file or a shipped name: its learner and budgets.
  // key=value applied to the config (the environment of Python's gpfd.assess); needs a config.
  std::vector<std::string> overrides;
  std::vector<FeatureSource> features;
  bool raw = false;                 // The original variables alone (always the baseline).
  bool withOriginal = false;        // Also each set + the original variables.
  int fourier = 0;                  // Order of a Fourier basis set to add; 0: none.
  int runs = 0;                     // Runs per set; 0: the config's.
  int budget = 0;                   // The learner's budget per run; 0: the config's.
  std::vector<std::string> params;  // k=v for the environment or the learner.
  std::uint64_t seed = 1;
  int threads = 0;
  // Trains the runs (e.g. the Python package's worker processes); empty: `threads` threads.
  std::shared_ptr<run::TrialRunner> trialRunner;
  OutputChoice out;                   // Default: results/assess-ENV.
  bool write = true;                  // Write the results (else only return the table).
  std::string where = "gpfd assess";  // How errors name the request.
};

struct AssessResult {
  std::string dir;  // Empty when nothing was written.
  run::ExperimentConfig config;
  std::vector<run::SetSummary> summary;
  int diverged = 0;  // Runs, over every set, whose learning diverged.
  long runs = 0;     // Runs, over every set.
};

// Runs the request; `print` (optional) gets the header and the table as text. Besides the sets
// asked for (the original variables first, the baseline), every assessment trains the no-learning
// reference (run::TrialFeatures::noLearning), the last row, named "no-learning". InputError, before
// anything is written, for a bad request.
AssessResult assess(const AssessRequest& request, const TextSink& print = {});

}  // namespace gpfd::service
