// A plug-in for tests/run/plugin_test.cpp, tests/rl/lockstep_plugin_test.cpp and the MPI tests
// across hosts (tests/mpi/multihost_test.py), built like examples/mountain-car (it links
// gpfd::plugin only): environments "walk" and "drift" and learners "hill" and "sleep", each
// registered with one line.
//   walk: a point on a line; the action moves it; reward -|x| per step; 20 steps.
//   drift: a point with a velocity; the action accelerates it; reward -x^2 per step; ends when
//          |x| > 2 or after max_steps. It declares a batched form (env/batch.hpp) that steps its
//          lanes with the same arithmetic; at exit it prints how many steps each form made.
//   hill: hill climbing over linear deterministic policies: each update perturbs the weights
//         (Gaussian, `noise`) and keeps them when one episode returns more.
//   sleep: a stand-in for a costly learner (a training of `ms` milliseconds that needs no core):
//          sleeps, then plays `episodes` episodes with every weight 1 (action = the sum of the
//          features), one point of its curve each. The MPI tests use it to time faults within a
//          generation, and scripts/multihost-scaling for evaluations of a chosen cost.
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "gpfd/env/batch.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/plugin.hpp"

namespace {

using namespace gpfd;

struct WalkConfig {
  double start = 1.0;  // x at reset.
  static const ParamTable<WalkConfig>& table() {
    static const auto table = ParamTable<WalkConfig>("walk").real(
        "start", [](auto& c) -> auto& { return c.start; }, -10.0, 10.0, "x at reset");
    return table;
  }
};

class Walk final : public env::Environment {
 public:
  explicit Walk(WalkConfig config) : config_(config) {}
  std::string name() const override { return "walk"; }
  env::Params params() const override { return WalkConfig::table().write(config_); }
  const std::vector<std::string>& stateNames() const override {
    static const std::vector<std::string> names{"x"};
    return names;
  }
  env::ActionSpace actionSpace() const override {
    env::ActionSpace space;
    space.low = {-1.0};
    space.high = {1.0};
    space.names = {"move"};
    return space;
  }
  void reset(Rng&) override {
    x_ = config_.start;
    steps_ = 0;
  }
  std::span<const double> state() const override { return {&x_, 1}; }
  void setState(std::span<const double> s) override { x_ = s[0]; }
  env::StepResult step(std::span<const double> action) override {
    x_ += std::isnan(action[0]) ? 0.0 : std::fmax(-1.0, std::fmin(1.0, action[0]));
    return {-std::fabs(x_), false, ++steps_ >= 20};
  }
  std::vector<env::StateRange> typicalStateRanges() const override { return {{-10.0, 10.0}}; }

 private:
  WalkConfig config_;
  double x_ = 0.0;
  int steps_ = 0;
};

struct DriftConfig {
  int maxSteps = 60;
  static const ParamTable<DriftConfig>& table() {
    static const auto table = ParamTable<DriftConfig>("drift").integer(
        "max_steps", [](auto& c) -> auto& { return c.maxSteps; }, 1, 100000, "time limit");
    return table;
  }
};

// The steps each form made, printed at exit (when any): what the tests read.
struct StepCounts {
  std::atomic<long> scalar{0}, lanes{0};
  ~StepCounts() {
    if (scalar > 0 || lanes > 0) {
      std::fprintf(stderr, "drift steps: %ld by step(), %ld by the batched form\n", scalar.load(),
                   lanes.load());
    }
  }
} counts;

// One step of the dynamics, shared by both forms: returns the reward, sets `terminated`.
double advance(double& x, double& v, double a, bool& terminated) {
  a = std::isnan(a) ? 0.0 : std::fmax(-1.0, std::fmin(1.0, a));
  v += 0.1 * a;
  x += 0.1 * v;
  terminated = std::fabs(x) > 2.0;
  return -x * x;
}

class Drift final : public env::Environment {
 public:
  explicit Drift(DriftConfig config) : config_(config) {}
  std::string name() const override { return "drift"; }
  env::Params params() const override { return DriftConfig::table().write(config_); }
  const std::vector<std::string>& stateNames() const override {
    static const std::vector<std::string> names{"x", "v"};
    return names;
  }
  env::ActionSpace actionSpace() const override {
    env::ActionSpace space;
    space.low = {-1.0};
    space.high = {1.0};
    space.names = {"push"};
    return space;
  }
  void reset(Rng& rng) override {
    s_[0] = rng.uniform(-1.0, 1.0);
    s_[1] = 0.0;
    steps_ = 0;
  }
  std::span<const double> state() const override { return s_; }
  void setState(std::span<const double> s) override { s_ = {s[0], s[1]}; }
  env::StepResult step(std::span<const double> action) override {
    ++counts.scalar;
    bool terminated = false;
    const double reward = advance(s_[0], s_[1], action[0], terminated);
    return {reward, terminated, ++steps_ >= config_.maxSteps};
  }
  std::vector<env::StateRange> typicalStateRanges() const override {
    return {{-2.0, 2.0}, {-1.0, 1.0}};
  }
  int maxSteps() const { return config_.maxSteps; }

 private:
  DriftConfig config_;
  std::array<double, 2> s_{};
  int steps_ = 0;
};

// Drift's batched form: lane by lane with advance(), as step() does (no vector instructions).
class DriftBatch final : public env::BatchEnvironment {
 public:
  DriftBatch(const Drift& drift, env::BatchIsa isa)
      : BatchEnvironment(std::make_unique<Drift>(DriftConfig::table().read(drift.params())), isa),
        maxSteps_(drift.maxSteps()) {}
  void step(const env::BatchBuffers& io) const override {
    for (std::size_t l = 0; l < io.lanes; ++l) {
      bool terminated = false;
      io.reward[l] = advance(io.state[l], io.state[io.stride + l], io.action[l], terminated);
      io.terminated[l] = terminated ? 1 : 0;
      io.truncated[l] = ++io.elapsed[l] >= maxSteps_ ? 1 : 0;
    }
    counts.lanes += static_cast<long>(io.lanes);
  }

 private:
  int maxSteps_;
};

// The return of one episode with action = weights . features (one continuous action).
double episode(env::Environment& env, const features::FeatureMap& map,
               const rl::LinearWeights& weights, Rng& rng, rl::LearningCurve& counters) {
  std::vector<double> phi(map.outputDim());
  double total = 0.0;
  env.reset(rng);
  for (;;) {
    map.evaluate(env.state().data(), phi.data());
    double action = 0.0;
    for (std::size_t i = 0; i < phi.size(); ++i) action += weights.values[i] * phi[i];
    const auto result = env.step(std::span<const double>(&action, 1));
    total += result.reward;
    ++counters.steps;
    if (result.terminated || result.truncated) break;
  }
  ++counters.episodes;
  return total;
}

// Hill and sleep: learners of linear deterministic policies, evaluated by the mean return of
// `episodes` episodes.
class LinearPolicyLearner : public rl::Learner {
 public:
  rl::Evaluation evaluate(env::Environment& env, const features::FeatureMap& map,
                          const rl::LinearWeights& weights, int episodes, Rng& rng) const override {
    rl::LearningCurve counters;
    double sum = 0.0;
    for (int e = 0; e < episodes; ++e) sum += episode(env, map, weights, rng, counters);
    return {episodes, episodes > 0 ? sum / episodes : 0.0, counters.steps, false};
  }
};

// Why hill and sleep cannot learn on `env` (empty when they can).
std::string unsuitable(env::Environment& env) {
  const auto space = env.actionSpace();
  return space.continuous() && space.components == 1 ? ""
                                                     : "it has not exactly one continuous action";
}

struct HillConfig {
  int updates = 10;
  double noise = 0.5;
  static const ParamTable<HillConfig>& table() {
    static const auto table = ParamTable<HillConfig>("hill")
                                  .integer(
                                      "updates", [](auto& c) -> auto& { return c.updates; }, 0,
                                      100000, "perturbations tried")
                                  .real(
                                      "noise", [](auto& c) -> auto& { return c.noise; }, 0.0, 10.0,
                                      "standard deviation of a perturbation");
    return table;
  }
};

class Hill final : public LinearPolicyLearner {
 public:
  explicit Hill(HillConfig config) : config_(config) {}

  rl::LearningCurve train(env::Environment& env, const features::FeatureMap& map, Rng& rng,
                          const rl::PointCallback& onPoint) const override {
    rl::LearningCurve curve;
    curve.weights.rows = 1;
    curve.weights.cols = map.outputDim();
    curve.weights.values.assign(map.outputDim(), 0.0);
    double best = episode(env, map, curve.weights, rng, curve);
    for (int u = 0; u <= config_.updates; ++u) {
      if (u > 0) {
        rl::LinearWeights trial = curve.weights;
        for (double& w : trial.values) w += config_.noise * rng.normal();
        const double value = episode(env, map, trial, rng, curve);
        if (value > best) {
          best = value;
          curve.weights = trial;
        }
      }
      curve.points.push_back({u, curve.episodes, curve.steps, best});
      if (onPoint) onPoint(curve.points.back());
    }
    return curve;
  }

 private:
  HillConfig config_;
};

struct SleepConfig {
  double ms = 10.0;
  int episodes = 1;
  static const ParamTable<SleepConfig>& table() {
    static const auto table = ParamTable<SleepConfig>("sleep")
                                  .real(
                                      "ms", [](auto& c) -> auto& { return c.ms; }, 0.0, 3.6e6,
                                      "milliseconds asleep per training")
                                  .integer(
                                      "episodes", [](auto& c) -> auto& { return c.episodes; }, 1,
                                      100000, "episodes played after the sleep");
    return table;
  }
};

class Sleep final : public LinearPolicyLearner {
 public:
  explicit Sleep(SleepConfig config) : config_(config) {}

  rl::LearningCurve train(env::Environment& env, const features::FeatureMap& map, Rng& rng,
                          const rl::PointCallback& onPoint) const override {
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(config_.ms));
    rl::LearningCurve curve;
    curve.weights.rows = 1;
    curve.weights.cols = map.outputDim();
    curve.weights.values.assign(map.outputDim(), 1.0);
    for (int e = 0; e < config_.episodes; ++e) {
      const double value = episode(env, map, curve.weights, rng, curve);
      curve.points.push_back({e, curve.episodes, curve.steps, value});
      if (onPoint) onPoint(curve.points.back());
    }
    return curve;
  }

 private:
  SleepConfig config_;
};

void registerAll(PluginRegistries& r) {
  r.environments.add(
      {"walk", "a point on a line (a test plug-in)", WalkConfig::table().specs(),
       [](const env::Params& p) { return std::make_unique<Walk>(WalkConfig::table().read(p)); }});
  r.environments.add(
      {"drift",
       "a point with a velocity, with a batched form (a test plug-in)",
       DriftConfig::table().specs(),
       [](const env::Params& p) { return std::make_unique<Drift>(DriftConfig::table().read(p)); },
       "pg",
       {.available = nullptr, .make = [](const env::Environment& prototype, env::BatchIsa isa) {
          return std::make_unique<DriftBatch>(dynamic_cast<const Drift&>(prototype), isa);
        }}});
  r.learners.add(
      {"hill",
       "hill climbing over linear policies (a test plug-in)",
       HillConfig::table().specs(),
       [](const Params& p) { return std::make_unique<Hill>(HillConfig::table().read(p)); },
       "one continuous action",
       unsuitable,
       "updates",
       "perturbation",
       {}});
  r.learners.add(
      {"sleep",
       "sleeps, then plays with every weight 1 (a test plug-in)",
       SleepConfig::table().specs(),
       [](const Params& p) { return std::make_unique<Sleep>(SleepConfig::table().read(p)); },
       "one continuous action",
       unsuitable,
       "episodes",
       "episode",
       {}});
}

}  // namespace

GPFD_PLUGIN(registerAll)
