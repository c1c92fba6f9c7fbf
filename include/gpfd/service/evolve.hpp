// service: feature discovery as one request (`gpfd evolve`, Python's gpfd.evolve): the config
// read, the results directory chosen and locked, a single run or a set of runs started or
// resumed, and its progress reported to whoever asked. The front ends only translate their
// arguments into an EvolveRequest and the result into their own output.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpfd/run/discovery.hpp"
#include "gpfd/run/run_set.hpp"
#include "gpfd/service/results_directory.hpp"

namespace gpfd::service {

struct EvolveRequest {
  std::string config;                  // A file or a shipped config name; empty: the default.
  std::vector<std::string> overrides;  // key=value (--set; the flags --env, --seed, ... as keys).
  OutputChoice out;                    // The results directory (default results/<name>).
  std::string resume;                  // Continue the run or set of runs in this directory.
  // Rerun the finished run in this directory with the sizes and learner settings it used
  // (run/replay.hpp), into a fresh directory (`out`, default results/<its name>-replay); no
  // overrides, runs or generations.
  std::string replay;
  std::optional<int> generations;  // Extends a resumed run (a fresh one: an override).
  std::optional<int> runs;         // Independent runs (a set); default 1.
  int threads = 0;                 // 0: all cores. Never changes results.
  // How the evaluations are spread (MPI, Python worker processes); empty: threads.
  run::EvaluatorFactory makeEvaluator;
  // Where validation and confirmation train (Python worker processes); empty: threads.
  std::shared_ptr<run::TrialRunner> trialRunner;
  // The default results directory, results/NAME (-2, -3, ... when taken); empty: the config's
  // name. A plain name (run::isRunName), else InputError.
  std::string outName;
  int processes = 1;  // MPI processes, recorded in run.json when above 1.
  // run.json's "env" of each run started (run::DiscoveryOptions::envJson); empty: none.
  std::string envJson;
};

// What the request sees of a run while it goes. `label` names a run within a set ("[run 2/3] "),
// empty for a single run; `dir` is the run's directory, `resumeDir` the one to resume.
class EvolveProgress {
 public:
  virtual ~EvolveProgress() = default;
  virtual void runStarted(const run::Discovery&, const std::string& /*dir*/,
                          const std::string& /*label*/) {}
  // After each generation, once its checkpoint is written. May throw to stop the run there.
  virtual void generationDone(const run::Discovery&, const run::GenerationRecord&,
                              const std::string& /*label*/) {}
  // The run ended without finishing: interrupted (`error` false) or failed (true; the error
  // is rethrown after this call). Its last checkpoint is written.
  virtual void runStopped(const run::Discovery&, const std::string& /*dir*/,
                          const std::string& /*resumeDir*/, bool /*error*/) {}
  virtual void runFinished(const run::RunOutcome&, const std::string& /*dir*/,
                           const std::string& /*label*/) {}
  virtual void setFinished(const std::vector<run::RunOutcome>&, const std::string& /*dir*/) {}
  // A resumed run that had nothing left to do.
  virtual void alreadyComplete(const std::string& /*dir*/, int /*generations*/) {}
  // What was measured and chosen before any run, a line of text each: the learner's settings
  // chosen on the task (learner.choose), a time budget's measurement and the sizes it chose.
  virtual void preparedRun(const std::string& /*text*/) {}
  // A stage before any run starts, as it begins (a line of text without its end): choosing the
  // learner's settings, measuring what an evaluation costs.
  virtual void preparing(const std::string& /*phase*/) {}
};

struct EvolveResult {
  std::string dir;                        // The results directory (of the run, or of the set).
  bool finished = false;                  // Every run done and validated; false when stopped.
  std::vector<run::RunOutcome> outcomes;  // Of the finished runs, in order.
};

// The run in options.outDir: resumed from its checkpoint once it has been started there
// (config.toml; it must then have been started with `config` when given), else started with
// `config`; `generations` extends a resumed run or sets a fresh one's. The one place a run starts
// or resumes (evolve below, and gpfd reproduce's runs); the caller holds the directory's lock.
std::unique_ptr<run::Discovery> openRun(const std::optional<run::ExperimentConfig>& config,
                                        const run::DiscoveryOptions& options,
                                        std::optional<int> generations);

// Runs the request. `stop` is checked after each generation (once its checkpoint is written).
// InputError, before anything is written, for a bad request; the directory is locked for the
// whole call. A fresh single run that fails (or is interrupted) before its first generation ends
// leaves no directory that this call created.
EvolveResult evolve(const EvolveRequest& request, EvolveProgress& progress,
                    const std::atomic<bool>& stop);

}  // namespace gpfd::service
