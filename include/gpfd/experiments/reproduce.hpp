// experiments: `gpfd reproduce`, the paper's experiments regenerated with figures and a report:
//   fig1  cart-pole, PG + Rprop: original variables, original + sin/cos of the angle, GP features
//   fig3  the JIT speed-up (gpfd bench jit)
//   fig5  Acrobot: GP run, discovered vs original features
//   fig6  3- and 5-segment swimmer: as fig5 with the population's mean fitness; for 3 segments
//         the best-fitness curves with populations 25, 50 and 100
//   fig7  Tetris 12x8 with lambda-policy iteration: as fig6
// With several GP runs per benchmark (gpRuns), each run's returned features are assessed and the
// report gives the method-level verdict (method_verdict.hpp), written to OUT/<fig>/method-NAME.csv.
// Each experiment keeps its runs in OUT/<fig>/...; a rerun resumes unfinished GP runs and reuses
// finished steps, so a long paper-scale reproduction can be interrupted and continued.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "gpfd/run/experiment_config.hpp"

namespace gpfd::experiments {

struct ReproduceOptions {
  bool paperScale = false;  // false: the -quick configs.
  std::uint64_t seed = 1;
  std::string outDir = "results/reproduce";
  int threads = 0;
  std::string version, revision;
  bool quiet = false;
  // Leave out the Fourier-basis assessments (their own directories, assess-NAME-fourier): at the
  // paper's budget a basis that does not learn plays every episode to the step limit, which can
  // cost more than the rest of the experiment. A later run without the flag adds them.
  bool skipFourier = false;
  // Independent GP runs per benchmark (run r with seed runSeed(seed, r)); each run's features
  // are assessed against the original variables and the report gives the method-level verdict.
  int gpRuns = 1;
  // key=value overrides applied to every benchmark's config (e.g. to switch a behaviour off).
  std::vector<std::string> overrides;
  // An earlier reproduction (e.g. of the old behaviour) whose method-level results each
  // benchmark is compared with; empty: none.
  std::string baselineDir;
  const std::atomic<bool>* stop = nullptr;  // Set (e.g. by SIGINT) to stop after a checkpoint.
};

inline const std::vector<std::string> kFigures{"fig1", "fig3", "fig5", "fig6", "fig7"};

// Runs the given figures (a subset of kFigures) and writes OUT/report.md and OUT/report.html
// covering every figure present in OUT. InputError for an unknown figure name or when another
// process writes into OUT; Interrupted when `stop` was set (after the step that was running).
void reproduce(const std::vector<std::string>& figures, const ReproduceOptions& options);

}  // namespace gpfd::experiments
