// run: a feature-discovery run (`gpfd evolve`): GP whose fitness is learning performance in
// short trials, with its results directory, per-generation checkpoints and exact resume.
//
// Results directory:
//   config.toml              the fully resolved config
//   run.json                 seed, version, threads (and MPI processes, when above 1); with a
//                            time budget what it measured and chose, and "sizes": the sizes
//                            that came from the clock, the generations as fitted to the
//                            deadline (what `--replay` reruns); "replay_of" in a replay
//   generations.csv          one row per generation
//   best/generation-NNNN.features   the best genome of each generation, as the learner saw it
//                            (`# status: not validated`)
//   best.features            the GP's best features so far, likewise not validated; at the end
//                            what validation and confirmation return
//   validation.csv           the validated sets (hall of fame and original variables)
//   front.csv                the best validated set at each size
//   checkpoint.json          everything needed to continue exactly
// Every file is written atomically; a generation's files are written before its checkpoint.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "gpfd/gp/evaluator.hpp"
#include "gpfd/run/checkpoint.hpp"
#include "gpfd/run/experiment_config.hpp"
#include "gpfd/run/trial_runner.hpp"

namespace gpfd::run {

// What a run gives the factory of its evaluator.
struct EvaluatorSetup {
  const ExperimentConfig& config;     // The run's config (generations possibly extended).
  std::string configText;             // formatExperimentConfig(config): rebuilds the LearningTask.
  std::function<void()> onEvaluated;  // Call once per finished fitness (progress display).
  // 0: the GP's short trials; r > 0: successive halving's r-th longer rung (fitnessRungs), whose
  // config is `config`. A factory that cannot make such an evaluator throws InputError.
  int rung = 0;
};
using EvaluatorFactory = std::function<std::unique_ptr<gp::Evaluator>(const EvaluatorSetup&)>;

struct DiscoveryOptions {
  std::string outDir;
  int threads = 0;       // 0: all cores. Never changes results.
  std::string version;   // gpfd's version, recorded and checked on resume.
  std::string revision;  // Recorded only.
  // Makes the evaluator of trialFitness (e.g. MPI's); empty: a ThreadEvaluator with `threads`.
  // Whatever it makes must give ThreadEvaluator's results.
  EvaluatorFactory makeEvaluator;
  int processes = 1;  // MPI processes of the run; recorded in run.json when above 1.
  // Trains the validation and confirmation trials (e.g. the Python package's worker processes);
  // empty: a ThreadTrialRunner with `threads`. Whatever it is must give the same curves.
  std::shared_ptr<TrialRunner> trialRunner;
  // What a time budget measured and chose (run/time_budget.hpp), as JSON: run.json's
  // "time_budget"; empty: none.
  std::string timeBudgetJson;
  // A time budget's end: after each generation, gp.generations becomes the generations made and
  // those that still fit before `deadline` (each as long as the longest of the last three),
  // `finishSeconds` (validation and confirmation, predicted) kept free; written into config.toml
  // and the checkpoint. Unset: none.
  std::optional<std::chrono::steady_clock::time_point> deadline;
  double finishSeconds = 0.0;
  // The learner's settings tried and chosen (run/learner_choice.hpp), as JSON: run.json's
  // "learner_choice"; empty: none.
  std::string learnerChoiceJson;
  // What the front end knows of the task beyond the config, as a JSON object: run.json's "env"
  // (gpfd.evolve's fingerprint of an environment stepped in Python, which a resume checks);
  // empty: none.
  std::string envJson;
  // The run this one replays (run/replay.hpp): run.json's "replay_of"; empty: none.
  std::string replayOf;
  // With a deadline: validation's and confirmation's trainings as a multiple of one of the GP's
  // trial trainings; the time kept free for them is at least this many times the cost of a trial
  // training in the last generations (where the sets learn as the hall of fame will), not only
  // `finishSeconds`, measured before any set learned.
  double finishTrainings = 0.0;
};

// The evaluators of successive halving's longer rungs (fitnessRungs), shortest first: made by
// options.makeEvaluator (EvaluatorSetup::rung) or on options.threads threads; none when
// fitness.promote is 0.
std::vector<std::unique_ptr<gp::Evaluator>> makeRungEvaluators(const ExperimentConfig& config,
                                                               const DiscoveryOptions& options);

// InputError when `dir` already holds a run (checkpoint.json) or a set of runs (runs.json):
// neither a run nor a set is ever started over either.
void refuseExistingRuns(const std::string& dir);

// What a run is doing, for progress displays: its GP generations, the validation of the hall of
// fame (after the last generation, and every validation.every generations), or the confirmation
// of the winner. `done` of `total` trainings (validation: all at once; confirmation: a look at a
// time, and a clear difference ends it early).
struct RunStage {
  enum Kind { Generations, Validation, Confirmation };
  Kind kind = Generations;
  int done = 0;
  int total = 0;
  // The run's generations as the config holds them now (a time budget's deadline refits them
  // after each generation).
  int generations = 0;
};
const char* stageName(RunStage::Kind kind);

class Discovery {
 public:
  // A fresh run in options.outDir, which must not already hold a run or a set of runs
  // (refuseExistingRuns). Validates everything before creating anything; InputError otherwise.
  static std::unique_ptr<Discovery> start(const ExperimentConfig& config,
                                          const DiscoveryOptions& options);
  // Continues the run in options.outDir from its checkpoint, with its stored config. When
  // `expected` is given it must equal the stored config. `generations` may extend the run.
  // InputError for a missing or corrupt checkpoint, another version, or another config.
  static std::unique_ptr<Discovery> resume(const DiscoveryOptions& options,
                                           const std::optional<ExperimentConfig>& expected,
                                           std::optional<int> generations);
  ~Discovery();

  // Runs generations until the configured number exist or `stop` becomes true (checked after
  // each generation, once its checkpoint is written), then the final validation (unless
  // stopped). `onGeneration` sees every new record.
  void run(const std::function<void(const GenerationRecord&)>& onGeneration,
           const std::atomic<bool>& stop);

  const ExperimentConfig& config() const;
  std::size_t stateDim() const;
  const std::vector<GenerationRecord>& history() const;
  // Every generation done and, when validating, the winner chosen.
  bool finished() const;
  const ValidationState& validation() const;
  // A genome as the learner sees it (normalised, placeholders out), simplified: what the run's
  // features files hold for it.
  expr::Genome asLearnerSees(const expr::Genome& genome) const;
  // Evaluations completed in the current generation (for progress displays; any thread).
  long progress() const;
  int populationSize() const;
  // The stage running now (any thread; its fields are read one at a time).
  RunStage stage() const;

 private:
  struct State;
  explicit Discovery(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
};

}  // namespace gpfd::run
