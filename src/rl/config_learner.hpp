// rl: the Learner of a linear learner whose training is a pair of free functions over its config:
// one run (Train) and several runs side by side (TrainRuns), as policy gradient and ARS have.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "gpfd/rl/learner.hpp"

namespace gpfd::rl {

// Config has onPoint, onRunPoint and lockstep. Train(env, map, config, rng) and
// TrainRuns(env, map, config, rngs) must give the same curves for the same engines.
template <class Config, auto Train, auto TrainRuns>
class ConfigLearner : public Learner {
 public:
  explicit ConfigLearner(Config config) : config_(std::move(config)) {}

  LearningCurve train(env::Environment& env, const features::FeatureMap& map, Rng& rng,
                      const PointCallback& onPoint) const override {
    Config config = config_;
    config.onPoint = onPoint;
    return Train(env, map, config, rng);
  }

  // With lockstep, the runs' episodes are played side by side (TrainRuns) on one environment
  // made by makeEnv; without, one run after another, each on its own environment (the
  // reference). Both give the same curves.
  std::vector<LearningCurve> trainRuns(const EnvironmentMaker& makeEnv,
                                       const features::FeatureMap& map, std::span<Rng> rngs,
                                       const RunPointCallback& onPoint) const override {
    if (!config_.lockstep) return Learner::trainRuns(makeEnv, map, rngs, onPoint);
    const auto env = makeEnv();
    Config config = config_;
    config.onRunPoint = onPoint;
    return TrainRuns(*env, map, config, rngs);
  }

 protected:
  const Config& config() const { return config_; }

 private:
  Config config_;
};

}  // namespace gpfd::rl
