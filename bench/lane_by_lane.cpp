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

#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "gpfd/env/batch.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/rl/policy_gradient.hpp"

namespace {

using namespace gpfd;

// Cart-pole under another name, without a batched form.
class UnbatchedCartPole final : public env::Environment {
 public:
  explicit UnbatchedCartPole(env::CartPoleConfig config) : inner_(config) {}
  std::string name() const override { return "cartpole-unbatched"; }
  env::Params params() const override { return inner_.params(); }
  const std::vector<std::string>& stateNames() const override { return inner_.stateNames(); }
  env::ActionSpace actionSpace() const override { return inner_.actionSpace(); }
  void reset(Rng& rng) override { inner_.reset(rng); }
  std::span<const double> state() const override { return inner_.state(); }
  void setState(std::span<const double> state) override { inner_.setState(state); }
  env::StepResult step(std::span<const double> action) override { return inner_.step(action); }

 private:
  env::CartPole inner_;
};

const bool kRegistered = [] {
  env::Registry::global().add({"cartpole-unbatched", "cart-pole without a batched form (bench)",
                               env::CartPoleConfig::table().specs(), [](const Params& p) {
                                 return std::make_unique<UnbatchedCartPole>(
                                     env::CartPoleConfig::fromParams(p));
                               }});
  return true;
}();

double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Path {
  double seconds = 0.0;
  std::int64_t steps = 0;

  template <class Run>
  void time(Run&& run) {
    const double start = threadSeconds();
    steps += run();
    seconds += threadSeconds() - start;
  }
  double nsPerStep() const { return steps > 0 ? 1e9 * seconds / static_cast<double>(steps) : 0.0; }
};

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
  if (slow.steps != quick.steps) state.SkipWithError("the paths played different steps");
  state.counters["sequential_ns/step"] = slow.nsPerStep();
  state.counters["lane_by_lane_ns/step"] = quick.nsPerStep();
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
