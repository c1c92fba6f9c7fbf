// Lockstep on environments without a batched form, side by side in one run: the lockstep player
// stepping copies of the environment lane by lane (env::makeLaneByLaneBatch) against the
// sequential path such environments took before (episodes one after another). Each iteration plays
// the same work on both paths (same seeds, so the same episodes and steps), timed by the CPU time
// of this thread. Counters: ns per environment step of each path, and their ratio (speedup > 1:
// lane by lane is faster).
//   PgTrial: one run (trainPolicyGradient, 10 episodes per update); reference lockstep=false.
//   PgFitness: the trials of one fitness evaluation; reference = one trial after another
//   (Learner::trainRuns), fast = trainPolicyGradientRuns with lockstep.
// Environments: "cartpole-unbatched" (cart-pole's dynamics behind a wrapper that declares no
// batched form: a cheap step, where the per-lane overhead shows most) and the 9-segment swimmer
// (beyond the fixed-size kernel: an expensive step).
//   build/release/bench/bench_lane_by_lane --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "../tests/rl/unbatched_cartpole.hpp"
#include "gpfd/env/batch.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/rl/policy_gradient.hpp"
#include "side_by_side.hpp"

namespace {

using namespace gpfd;

using bench::Path;

struct Trial {
  std::string env;
  Params envParams;
  std::string features;
  int trials = 4;  // Of a fitness evaluation.
};

const Trial kCartPole{
    "cartpole-unbatched", {{"max_steps", "1000"}}, "dx\n2 * th\nth / 0.1888\nsin(dth)\n", 5};
const Trial kSwimmer9{
    "swimmer", {{"segments", "9"}, {"horizon", "100"}}, "th1\nsin(th5)\ndth2\n", 4};

void run(benchmark::State& state, const Trial& trial, bool fitness) {
  testing::registerUnbatchedCartPole("cartpole-unbatched");
  const auto environment = env::Registry::global().make(trial.env, trial.envParams);
  if (env::hasBatchEnvironment(*environment) || !env::makeLaneByLaneBatch(*environment)) {
    state.SkipWithError("the environment must have no batched form and be copyable");
    return;
  }
  const jit::CompiledFeatureMap map(
      expr::parseFeaturesFile(trial.features, "bench", environment->stateNames(),
                              environment->name())
          .genome,
      environment->stateDim());
  rl::PolicyGradientConfig reference;
  reference.updates = 30;
  reference.episodesPerUpdate = 10;
  reference.lockstep = false;
  rl::PolicyGradientConfig fast = reference;
  fast.lockstep = true;
  Path slow, quick;
  std::uint64_t seed = 0;
  const int runs = fitness ? trial.trials : 1;
  for (auto _ : state) {
    ++seed;
    slow.time([&] {
      std::int64_t steps = 0;
      for (int t = 0; t < runs; ++t) {
        Rng rng(deriveSeed(seed, t));
        steps += rl::trainPolicyGradient(*environment, map, reference, rng).steps;
      }
      return steps;
    });
    quick.time([&] {
      std::vector<Rng> rngs;
      for (int t = 0; t < runs; ++t) rngs.emplace_back(deriveSeed(seed, t));
      std::int64_t steps = 0;
      for (const auto& curve : rl::trainPolicyGradientRuns(*environment, map, fast, rngs)) {
        steps += curve.steps;
      }
      return steps;
    });
  }
  if (slow.units != quick.units) state.SkipWithError("the paths played different steps");
  state.counters["sequential_ns/step"] = slow.nsPerUnit();
  state.counters["lane_by_lane_ns/step"] = quick.nsPerUnit();
  state.counters["speedup"] = quick.seconds > 0 ? slow.seconds / quick.seconds : 0.0;
}

void BM_PgTrialCartPoleUnbatched(benchmark::State& s) { run(s, kCartPole, false); }
void BM_PgFitnessCartPoleUnbatched(benchmark::State& s) { run(s, kCartPole, true); }
void BM_PgTrialSwimmer9(benchmark::State& s) { run(s, kSwimmer9, false); }
void BM_PgFitnessSwimmer9(benchmark::State& s) { run(s, kSwimmer9, true); }
BENCHMARK(BM_PgTrialCartPoleUnbatched)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_PgFitnessCartPoleUnbatched)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_PgTrialSwimmer9)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_PgFitnessSwimmer9)->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
