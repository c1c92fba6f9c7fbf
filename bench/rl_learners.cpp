// Speed of the learners, side by side in one run: each iteration plays the same short trial (same
// seed, so the same episodes and steps) on the reference path and on the fast path, and times
// each by the CPU time of this thread (so that other processes on a shared machine disturb the
// ratio little). Counters: ns per environment step (PG) or per decision (lambda-PI) of each path,
// and their ratio.
//   PG trials (cart-pole, Acrobot, 3- and 5-segment swimmer; the configs' short trials, with
//   features of the kind GP discovers): reference = episodes one after another (lockstep=false),
//   fast = lockstep episodes through the batched environment.
//   GP fitness (the trials of one evaluation through run::trialFitness): reference = the trials
//   one after another, fast = played together.
//   ARS fitness (the same trials' environments, features and iterations, ARS's defaults):
//   reference = trials and episodes one after another, fast = lockstep lanes of every trial.
//   Tetris lambda-PI (12 x 8, the 18 variables, Bertsekas-Ioffe start): reference = afterstates
//   placement by placement, fast = afterstates in bulk.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/rl/ars.hpp"
#include "gpfd/rl/game_afterstates.hpp"
#include "gpfd/rl/lambda_policy_iteration.hpp"
#include "gpfd/rl/policy_gradient.hpp"
#include "gpfd/run/learning_task.hpp"
#include "side_by_side.hpp"

namespace {

using namespace gpfd;

using bench::Path;

void report(benchmark::State& state, const Path& reference, const Path& fast, const char* unit) {
  state.counters[std::string("reference_ns/") + unit] = reference.nsPerUnit();
  state.counters[std::string("fast_ns/") + unit] = fast.nsPerUnit();
  state.counters["speedup"] = fast.seconds > 0 ? reference.seconds / fast.seconds : 0.0;
}

struct PgTrial {
  std::string env;
  Params envParams;
  std::string features;  // A features file over the state variables.
  int updates = 30;
  int episodes = 10;
  double std = 0.0;  // The policy's initial standard deviation; 0: the learner's default.
};

// A trial's environment, compiled features, and the learner settings of both paths.
struct PgSetup {
  explicit PgSetup(const PgTrial& trial)
      : environment(env::Registry::global().make(trial.env, trial.envParams)),
        map(expr::parseFeaturesFile(trial.features, "bench", environment->stateNames(),
                                    environment->name())
                .genome,
            environment->stateDim()) {
    reference.updates = trial.updates;
    reference.episodesPerUpdate = trial.episodes;
    if (trial.std > 0) reference.policy.initialStd = trial.std;
    fast = reference;
    reference.lockstep = false;
    fast.lockstep = true;
  }

  std::unique_ptr<env::Environment> environment;
  jit::CompiledFeatureMap map;
  rl::PolicyGradientConfig reference, fast;
};

void pgTrial(benchmark::State& state, const PgTrial& trial) {
  PgSetup s(trial);
  env::Environment& environment = *s.environment;
  Path slow, quick;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    ++seed;
    slow.time([&] {
      Rng rng(seed);
      return rl::trainPolicyGradient(environment, s.map, s.reference, rng).steps;
    });
    quick.time([&] {
      Rng rng(seed);
      return rl::trainPolicyGradient(environment, s.map, s.fast, rng).steps;
    });
  }
  report(state, slow, quick, "step");
}

// The configs' short trials (configs/*-quick.toml), with features like the ones GP found there.
const PgTrial kCartPole{
    "cartpole", {{"max_steps", "1000"}}, "dx\n2 * th\nth / 0.1888\nsin(dth)\n", 30, 10};
const PgTrial kAcrobot{"acrobot",
                       {{"max_steps", "3000"}},
                       "sin(th1)\ncos(th1)\nsin(th2)\ncos(th2)\ndth1\ndth2\n"
                       "sin(th1 + th2) * dth1\ncos(th1 + th2)\n",
                       30,
                       10,
                       1.0};
const PgTrial kSwimmer3{"swimmer",
                        {{"segments", "3"}, {"horizon", "100"}},
                        "sin(th2)\nth2 - dth1\n2 * th1\nth2\n",
                        30,
                        10};
const PgTrial kSwimmer5{
    "swimmer", {{"segments", "5"}, {"horizon", "100"}}, "th1\nsin(th5)\ndth2\n", 30, 10};

// The trials of one fitness evaluation (configs' `trials`: 5 on cart-pole and Acrobot, 4 on the
// swimmers): reference = one trial after another, episodes one after another; fast = every
// trial's episodes of an update side by side (trainPolicyGradientRuns).
void pgFitness(benchmark::State& state, const PgTrial& trial, int trials) {
  PgSetup s(trial);
  env::Environment& environment = *s.environment;
  Path slow, quick;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    ++seed;
    slow.time([&] {
      std::int64_t steps = 0;
      for (int t = 0; t < trials; ++t) {
        Rng rng(deriveSeed(seed, t));
        steps += rl::trainPolicyGradient(environment, s.map, s.reference, rng).steps;
      }
      return steps;
    });
    quick.time([&] {
      std::vector<Rng> rngs;
      for (int t = 0; t < trials; ++t) rngs.emplace_back(deriveSeed(seed, t));
      std::int64_t steps = 0;
      for (const auto& curve : rl::trainPolicyGradientRuns(environment, s.map, s.fast, rngs)) {
        steps += curve.steps;
      }
      return steps;
    });
  }
  report(state, slow, quick, "step");
}

// A GP fitness evaluation as `gpfd evolve` runs it (run::trialFitness on a LearningTask with the
// trial's settings, lockstep on): reference = its trials one after another, each on a fresh
// environment (LearningTask::train, as before the trials were played together); fast =
// trialFitness, which trains them together (LearningTask::trainRuns). Unit: one evaluation.
void trialFitness(benchmark::State& state, const PgTrial& trial, int trials) {
  run::ExperimentConfig config;
  config.env = trial.env;
  config.envParams = trial.envParams;
  config.learner = "pg";
  config.learnerParams = {{"updates", std::to_string(trial.updates)},
                          {"episodes", std::to_string(trial.episodes)}};
  if (trial.std > 0) config.learnerParams["std"] = std::to_string(trial.std);
  config.trials = trials;
  config.dropRedundant = false;
  const run::LearningTask task(config, run::LearningTask::Budget::Trial);
  const expr::Genome genome =
      expr::parseFeaturesFile(trial.features, "bench", task.stateNames(), trial.env).genome;
  Path slow, quick;
  std::uint64_t seed = 0;
  double sum = 0.0;
  for (auto _ : state) {
    ++seed;
    slow.time([&] {
      const auto map = task.featureMap(genome);
      Rng rng(seed);
      const std::uint64_t base = rng();
      for (int t = 0; t < trials; ++t) {
        Rng trialRng(deriveSeed(base, t));
        sum += task.score(task.train(*map, trialRng));
      }
      return 1;
    });
    quick.time([&] {
      Rng rng(seed);
      sum += run::trialFitness(task, genome, rng);
      return 1;
    });
  }
  benchmark::DoNotOptimize(sum);
  report(state, slow, quick, "evaluation");
}

// ARS (rl/ars.hpp, default settings: 8 directions, 16 episodes an iteration) on the same trials'
// environments, features and iterations, K trials of a fitness evaluation: reference = one trial
// after another, episodes one after another (lockstep=false); fast = every trial's episodes of
// an iteration side by side (trainArsRuns, K x 16 lanes).
void arsFitness(benchmark::State& state, const PgTrial& trial, int trials) {
  PgSetup s(trial);
  env::Environment& environment = *s.environment;
  rl::ArsConfig reference;
  reference.updates = trial.updates;
  reference.lockstep = false;
  rl::ArsConfig fast = reference;
  fast.lockstep = true;
  Path slow, quick;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    ++seed;
    slow.time([&] {
      std::int64_t steps = 0;
      for (int t = 0; t < trials; ++t) {
        Rng rng(deriveSeed(seed, t));
        steps += rl::trainArs(environment, s.map, reference, rng).steps;
      }
      return steps;
    });
    quick.time([&] {
      std::vector<Rng> rngs;
      for (int t = 0; t < trials; ++t) rngs.emplace_back(deriveSeed(seed, t));
      std::int64_t steps = 0;
      for (const auto& curve : rl::trainArsRuns(environment, s.map, fast, rngs)) {
        steps += curve.steps;
      }
      return steps;
    });
  }
  report(state, slow, quick, "step");
}

// Registers BM_<kind><Env> for the four PG trials, in this order: run(state, trial, K) with K the
// trials of a fitness evaluation in their configs (5 on cart-pole and Acrobot, 4 on the swimmers).
template <class Run>
bool registerPerTrial(const std::string& kind, Run run) {
  const std::vector<std::tuple<std::string, const PgTrial*, int>> trials{
      {"CartPole", &kCartPole, 5},
      {"Acrobot", &kAcrobot, 5},
      {"Swimmer3", &kSwimmer3, 4},
      {"Swimmer5", &kSwimmer5, 4}};
  for (const auto& [name, trial, count] : trials) {
    benchmark::RegisterBenchmark(
        ("BM_" + kind + name).c_str(),
        [run, trial = trial, count = count](benchmark::State& state) { run(state, *trial, count); })
        ->Unit(benchmark::kMillisecond)
        ->MinTime(3.0);
  }
  return true;
}

const bool kPgRegistered =
    registerPerTrial("PgTrial", [](benchmark::State& state, const PgTrial& trial,
                                   int) { pgTrial(state, trial); }) &&
    registerPerTrial("PgFitness", pgFitness) && registerPerTrial("TrialFitness", trialFitness) &&
    registerPerTrial("ArsFitness", arsFitness);

// Lambda-PI on 12 x 8 with the paper's 18 state variables: 2 iterations of 10 games from the
// Bertsekas-Ioffe start (short games, so that a run takes milliseconds). Unit: a decision (one
// move: every placement of the piece evaluated and the best one played).
void BM_LpiTetris(benchmark::State& state) {
  env::Tetris tetris;
  rl::LambdaPolicyIterationConfig config;
  config.iterations = 2;
  config.gamesPerIteration = 10;
  // Bertsekas & Ioffe's weights (the same for both state layouts), then 0 for the bias.
  config.initialWeights =
      env::Tetris(env::TetrisConfig::fromParams({{"state", "bertsekas"}})).knownValueWeights();
  config.initialWeights.push_back(0.0);
  const features::RawFeatureMap map(tetris.stateDim());
  Path slow, quick;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    ++seed;
    for (const bool bulk : {false, true}) {
      (bulk ? quick : slow).time([&] {
        tetris.setBulkAfterstates(bulk);
        rl::GameAfterstateProblem problem(tetris, tetris);
        Rng rng(seed);
        return rl::trainLambdaPolicyIteration(problem, map, config, rng).steps;
      });
    }
  }
  report(state, slow, quick, "decision");
}
BENCHMARK(BM_LpiTetris)->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
