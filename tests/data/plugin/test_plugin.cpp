// A plug-in for tests/run/plugin_test.cpp, built like examples/mountain-car (it links gpfd::plugin
// only): an environment "walk" and a learner "hill", each registered with one line.
//   walk: a point on a line; the action moves it; reward -|x| per step; 20 steps.
//   hill: hill climbing over linear deterministic policies: each update perturbs the weights
//         (Gaussian, `noise`) and keeps them when one episode returns more.
#include <cmath>

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

class Hill final : public rl::Learner {
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

  rl::Evaluation evaluate(env::Environment& env, const features::FeatureMap& map,
                          const rl::LinearWeights& weights, int episodes, Rng& rng) const override {
    rl::LearningCurve counters;
    double sum = 0.0;
    for (int e = 0; e < episodes; ++e) sum += episode(env, map, weights, rng, counters);
    return {episodes, episodes > 0 ? sum / episodes : 0.0, counters.steps, false};
  }

 private:
  // The return of one episode with action = weights . features.
  static double episode(env::Environment& env, const features::FeatureMap& map,
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

  HillConfig config_;
};

void registerAll(PluginRegistries& r) {
  r.environments.add(
      {"walk", "a point on a line (a test plug-in)", WalkConfig::table().specs(),
       [](const env::Params& p) { return std::make_unique<Walk>(WalkConfig::table().read(p)); }});
  r.learners.add(
      {"hill", "hill climbing over linear policies (a test plug-in)", HillConfig::table().specs(),
       [](const Params& p) { return std::make_unique<Hill>(HillConfig::table().read(p)); },
       "one continuous action",
       [](env::Environment& env) {
         const auto space = env.actionSpace();
         return std::string(space.continuous() && space.components == 1
                                ? ""
                                : "it has not exactly one continuous action");
       },
       "updates", "perturbation"});
}

}  // namespace

GPFD_PLUGIN(registerAll)
