// Speed of the learners: episodes per second of a policy-gradient trial on Acrobot with 8
// compiled features, games per second of lambda-PI on 12 x 8 Tetris, and the learner's own share
// of a trial: each trial is timed beside a bare loop that makes the same number of environment
// steps and feature calls (random actions, no learner). Overhead = 1 - bare / trial, per step.
#include <benchmark/benchmark.h>

#include "gpfd/env/environment.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/rl/game_afterstates.hpp"
#include "gpfd/rl/lambda_policy_iteration.hpp"
#include "gpfd/rl/policy_gradient.hpp"

namespace {

using namespace gpfd;

jit::CompiledFeatureMap acrobotFeatures() {
  const auto file = expr::parseFeaturesFile(
      "sin(th1)\ncos(th1)\nsin(th2)\ncos(th2)\ndth1\ndth2\nsin(th1 + th2) * dth1\ncos(th1 + th2)\n",
      "bench", {"th1", "th2", "dth1", "dth2"}, "acrobot");
  return jit::CompiledFeatureMap(file.genome, 4);
}

// A PG trial: 20 updates of 10 episodes (210 episodes).
void BM_PgTrialAcrobot(benchmark::State& state) {
  const auto env = env::Registry::global().make("acrobot");
  const auto map = acrobotFeatures();
  rl::PolicyGradientConfig config;
  config.updates = 20;
  std::int64_t episodes = 0, steps = 0;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    Rng rng(++seed);
    const auto curve = rl::trainPolicyGradient(*env, map, config, rng);
    episodes += curve.episodes;
    steps += curve.steps;
  }
  state.counters["episodes/s"] =
      benchmark::Counter(static_cast<double>(episodes), benchmark::Counter::kIsRate);
  state.counters["ns/step"] = benchmark::Counter(
      static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PgTrialAcrobot)->Unit(benchmark::kMillisecond);

// The same work without the learner: reset, features and a step per step, random actions.
void BM_BareStepsAcrobot(benchmark::State& state) {
  const auto env = env::Registry::global().make("acrobot");
  const auto map = acrobotFeatures();
  std::vector<double> phi(map.outputDim());
  double action = 0.0;
  std::int64_t steps = 0;
  Rng rng(1);
  for (auto _ : state) {
    env->reset(rng);
    for (int t = 0; t < 500; ++t) {
      map.evaluate(env->state().data(), phi.data());
      benchmark::DoNotOptimize(phi.data());
      action = rng.uniform(-1.0, 1.0);
      const auto r = env->step(std::span<const double>(&action, 1));
      ++steps;
      if (r.terminated || r.truncated) break;
    }
  }
  state.counters["ns/step"] = benchmark::Counter(
      static_cast<double>(steps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_BareStepsAcrobot)->Unit(benchmark::kMillisecond);

// Lambda-PI on 12 x 8 with the paper's 18 state variables: 2 iterations of 10 games from the
// Bertsekas-Ioffe start (short games, so that a run takes milliseconds).
void BM_LpiTetris(benchmark::State& state) {
  env::Tetris tetris;
  rl::GameAfterstateProblem problem(tetris, tetris);
  const features::RawFeatureMap map(tetris.stateDim());
  rl::LambdaPolicyIterationConfig config;
  config.iterations = 2;
  config.gamesPerIteration = 10;
  // Bertsekas & Ioffe's weights (the same for both state layouts), then 0 for the bias.
  config.initialWeights =
      env::Tetris(env::TetrisConfig::fromParams({{"state", "bertsekas"}})).knownValueWeights();
  config.initialWeights.push_back(0.0);
  std::int64_t games = 0, moves = 0;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    Rng rng(++seed);
    const auto curve = rl::trainLambdaPolicyIteration(problem, map, config, rng);
    games += curve.episodes;
    moves += curve.steps;
  }
  state.counters["games/s"] =
      benchmark::Counter(static_cast<double>(games), benchmark::Counter::kIsRate);
  state.counters["ns/move"] = benchmark::Counter(
      static_cast<double>(moves), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_LpiTetris)->Unit(benchmark::kMillisecond);

// The same without the learner: afterstates, their features and a random non-ending move.
void BM_BareMovesTetris(benchmark::State& state) {
  env::Tetris tetris;
  rl::GameAfterstateProblem problem(tetris, tetris);
  const features::RawFeatureMap map(tetris.stateDim());
  std::vector<double> phi;
  std::int64_t moves = 0;
  Rng rng(1);
  for (auto _ : state) {
    problem.reset(rng);
    for (int t = 0; t < 100000; ++t) {
      const auto view = problem.candidates();
      if (view.count == 0) break;
      phi.resize(view.count * map.outputDim());
      map.evaluateBatch(view.states, view.count, phi.data());
      benchmark::DoNotOptimize(phi.data());
      const std::size_t pick = rng.below(view.count);
      ++moves;
      if (view.ends[pick]) break;
      problem.choose(pick, rng);
    }
  }
  state.counters["ns/move"] = benchmark::Counter(
      static_cast<double>(moves), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_BareMovesTetris)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
