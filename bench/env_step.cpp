// Steps per second of the benchmark environments (Google Benchmark). Compare Acrobot and cart-pole
// with Gymnasium side by side using bench/python_speed.py (see docs/python.md).
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "gpfd/env/batch.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/env/swimmer.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/util/cpu.hpp"

namespace {

using gpfd::Rng;
using namespace gpfd::env;

void stepOnRandomActions(benchmark::State& state, Environment& env);
void stepLanes(benchmark::State& state, BatchEnvironment& batch);

// Steps an environment on pre-drawn random actions, resetting at the end of an episode.
void stepEnvironment(benchmark::State& state, const std::string& name, const Params& params) {
  if (name == "tetris") {  // Legal actions depend on the piece: draw each one in the loop.
    auto env = Registry::global().make(name, params);
    Rng rng(1);
    env->reset(rng);
    std::vector<double> action(2);
    for (auto _ : state) {
      env->sampleAction(rng, action);
      if (env->step(action).terminated) env->reset(rng);
      benchmark::DoNotOptimize(env->state().data());
    }
    state.SetItemsProcessed(state.iterations());
    return;
  }
  stepOnRandomActions(state, *Registry::global().make(name, params));
}

// Steps `env` on 4096 pre-drawn random actions in turn, resetting at the end of an episode.
void stepOnRandomActions(benchmark::State& state, Environment& env) {
  Rng rng(1);
  env.reset(rng);
  const std::size_t components = env.actionSpace().components;
  std::vector<double> actions(4096 * components);
  for (std::size_t i = 0; i < 4096; ++i) {
    env.sampleAction(rng, std::span<double>(actions.data() + i * components, components));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const StepResult r =
        env.step(std::span<const double>(actions.data() + (i & 4095) * components, components));
    benchmark::DoNotOptimize(env.state().data());
    if (r.terminated || r.truncated) env.reset(rng);
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Acrobot(benchmark::State& s) { stepEnvironment(s, "acrobot", {}); }
void BM_AcrobotDiscrete(benchmark::State& s) {
  stepEnvironment(s, "acrobot", {{"actions", "discrete"}});
}
void BM_CartPole(benchmark::State& s) { stepEnvironment(s, "cartpole", {}); }
void BM_CartPoleDiscrete(benchmark::State& s) {
  stepEnvironment(s, "cartpole", {{"actions", "discrete"}});
}
void BM_CartPoleClsquare(benchmark::State& s) {
  stepEnvironment(s, "cartpole", {{"gravity", "9.81"}, {"integrator", "rk4"}, {"substeps", "10"}});
}
// Default swimmer step: 10 Euler integration steps of 0.01 s.
void BM_Swimmer(benchmark::State& s) {
  stepEnvironment(s, "swimmer", {{"segments", std::to_string(s.range(0))}});
}
// The same with the original solver (run-time sized Eigen matrices and PartialPivLU), to compare
// with BM_Swimmer in one run.
void BM_SwimmerReference(benchmark::State& s) {
  SwimmerConfig config;
  config.segments = static_cast<int>(s.range(0));
  Swimmer swimmer(config);
  swimmer.setReferenceSolver(true);
  stepOnRandomActions(s, swimmer);
}
// One integration step per control step (Euler; RK4), i.e. one / four solves of the system.
void BM_SwimmerOneEulerStep(benchmark::State& s) {
  stepEnvironment(s, "swimmer",
                  {{"segments", std::to_string(s.range(0))}, {"substeps", "1"}, {"dt", "0.01"}});
}
void BM_SwimmerOneRk4Step(benchmark::State& s) {
  stepEnvironment(s, "swimmer",
                  {{"segments", std::to_string(s.range(0))},
                   {"substeps", "1"},
                   {"dt", "0.01"},
                   {"integrator", "rk4"}});
}
void BM_TetrisStep(benchmark::State& s) { stepEnvironment(s, "tetris", {}); }

// One decision: every placement of the current piece with its state variables, over boards and
// pieces from random play.
void BM_TetrisDecision(benchmark::State& state) {
  TetrisConfig config;
  config.rows = static_cast<int>(state.range(0));
  config.cols = static_cast<int>(state.range(1));
  Tetris tetris(config);
  Rng rng(2);
  std::vector<Tetris> positions;
  tetris.reset(rng);
  std::vector<double> action(2);
  while (positions.size() < 256) {
    positions.push_back(tetris);
    tetris.sampleAction(rng, action);
    if (tetris.step(action).terminated) tetris.reset(rng);
  }
  TetrisAfterstates out;
  std::size_t i = 0, placements = 0;
  for (auto _ : state) {
    positions[i & 255].afterstates(out);
    placements += out.placements.size();
    benchmark::DoNotOptimize(out.features.data());
    ++i;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["placements"] =
      benchmark::Counter(static_cast<double>(placements) / static_cast<double>(i));
}

// The batched environment (env/batch.hpp): a batch of lanes from random starts stepped on random
// actions, each lane reset when its episode ends; ns per lane-step (items). Arguments: lanes, and
// 2 for AVX-512 lanes, 1 for AVX2 lanes or 0 for one lane at a time.
void stepBatch(benchmark::State& state, const std::string& name, const Params& params) {
  const BatchIsa isa = state.range(1) == 2   ? BatchIsa::Avx512
                       : state.range(1) == 1 ? BatchIsa::Avx2
                                             : BatchIsa::Scalar;
  if ((isa == BatchIsa::Avx2 && !gpfd::cpuHasAvx2()) ||
      (isa == BatchIsa::Avx512 && !gpfd::cpuHasAvx512())) {
    state.SkipWithError("instruction set not available");
    return;
  }
  stepLanes(state, *makeBatchEnvironment(name, params, isa));
}

// Steps `batch`'s state.range(0) lanes as stepBatch describes.
void stepLanes(benchmark::State& state, BatchEnvironment& batch) {
  const auto lanes = static_cast<std::size_t>(state.range(0));
  const std::size_t dim = batch.stateDim(), components = batch.actionComponents();
  std::vector<double> states(dim * lanes), rewards(lanes);
  std::vector<std::int32_t> elapsed(lanes);
  std::vector<std::uint8_t> terminated(lanes), truncated(lanes);
  Rng rng(1);
  // 64 pre-drawn action batches, used in turn.
  std::vector<double> actions(64 * components * lanes);
  const ActionSpace space = batch.scalar().actionSpace();
  for (std::size_t i = 0; i < actions.size(); ++i) {
    const std::size_t c = (i / lanes) % components;
    actions[i] = space.continuous() ? rng.uniform(space.low[c], space.high[c])
                                    : static_cast<double>(rng.below(space.choices.front()));
  }
  BatchBuffers io{lanes,          lanes,          states.data(),     nullptr,
                  elapsed.data(), rewards.data(), terminated.data(), truncated.data()};
  for (std::size_t l = 0; l < lanes; ++l) batch.reset(rng, io, l);
  std::size_t t = 0;
  for (auto _ : state) {
    io.action = actions.data() + (t++ & 63) * components * lanes;
    batch.step(io);
    for (std::size_t l = 0; l < lanes; ++l) {
      if (terminated[l] || truncated[l]) batch.reset(rng, io, l);
    }
    benchmark::DoNotOptimize(states.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(lanes));
}

void BM_BatchCartPole(benchmark::State& s) { stepBatch(s, "cartpole", {}); }
void BM_BatchAcrobot(benchmark::State& s) { stepBatch(s, "acrobot", {}); }
void BM_BatchSwimmer3(benchmark::State& s) { stepBatch(s, "swimmer", {{"segments", "3"}}); }
void BM_BatchSwimmer5(benchmark::State& s) { stepBatch(s, "swimmer", {{"segments", "5"}}); }
// The twins of Gymnasium's classic control (env/gymnasium_twin.hpp), one instance.
void BM_Twin(benchmark::State& s, const char* id) { stepEnvironment(s, id, {}); }
// Their lanes as the lockstep player steps them (makeLaneByLaneBatch: GymnasiumTwin::makeLanes);
// ns per lane-step. Argument: lanes.
void BM_TwinLanes(benchmark::State& s, const char* id) {
  stepLanes(s, *makeLaneByLaneBatch(*Registry::global().make(id, {}), BatchIsa::Scalar));
}

void batchArgs(benchmark::internal::Benchmark* b) {
  for (const int lanes : {1, 4, 10, 64}) b->Args({lanes, 0})->Args({lanes, 1})->Args({lanes, 2});
}

BENCHMARK(BM_Acrobot);
BENCHMARK(BM_AcrobotDiscrete);
BENCHMARK(BM_CartPole);
BENCHMARK(BM_CartPoleDiscrete);
BENCHMARK(BM_CartPoleClsquare);
BENCHMARK(BM_Swimmer)->Arg(3)->Arg(5);
BENCHMARK(BM_SwimmerReference)->Arg(3)->Arg(5);
BENCHMARK(BM_SwimmerOneEulerStep)->Arg(3)->Arg(5);
BENCHMARK(BM_SwimmerOneRk4Step)->Arg(3)->Arg(5);
BENCHMARK(BM_TetrisStep);
BENCHMARK(BM_TetrisDecision)->Args({12, 8})->Args({20, 10});
BENCHMARK_CAPTURE(BM_Twin, CartPole, "CartPole-v1");
BENCHMARK_CAPTURE(BM_Twin, Acrobot, "Acrobot-v1");
BENCHMARK_CAPTURE(BM_Twin, Pendulum, "Pendulum-v1");
BENCHMARK_CAPTURE(BM_Twin, MountainCar, "MountainCar-v0");
BENCHMARK_CAPTURE(BM_Twin, MountainCarContinuous, "MountainCarContinuous-v0");
BENCHMARK_CAPTURE(BM_TwinLanes, CartPole, "CartPole-v1")->Arg(20);
BENCHMARK_CAPTURE(BM_TwinLanes, Acrobot, "Acrobot-v1")->Arg(20);
BENCHMARK_CAPTURE(BM_TwinLanes, Pendulum, "Pendulum-v1")->Arg(20);
BENCHMARK_CAPTURE(BM_TwinLanes, MountainCar, "MountainCar-v0")->Arg(20);
BENCHMARK_CAPTURE(BM_TwinLanes, MountainCarContinuous, "MountainCarContinuous-v0")->Arg(20);
BENCHMARK(BM_BatchCartPole)->Apply(batchArgs);
BENCHMARK(BM_BatchAcrobot)->Apply(batchArgs);
BENCHMARK(BM_BatchSwimmer3)->Apply(batchArgs);
BENCHMARK(BM_BatchSwimmer5)->Apply(batchArgs);

}  // namespace

BENCHMARK_MAIN();
