// rl: how policy gradient plays the episodes of one policy update. Each episode draws everything
// (its start state, its actions) from its own random stream, seeded per episode, so the episodes
// can be played one after another (the sequential reference) or side by side in lockstep through
// the batched environment (env/batch.hpp) and the feature map's batch evaluation, with the same
// results bit for bit (tests/rl/lockstep_test.cpp).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/features.hpp"
#include "gpfd/rl/linear_policy.hpp"

namespace gpfd::rl::episodes {

struct Outcome {
  double undiscounted = 0.0;
  double discounted = 0.0;
  std::int64_t steps = 0;
  // False: a non-finite state, feature, action or reward; when sampling also a non-finite
  // discounted return or likelihood gradient. A player may skip the episodes after the first such
  // one.
  bool ok = true;
};

// What a player reports for the episodes of one call, in the order of its tasks.
struct Records {
  std::vector<Outcome> outcomes;
  std::vector<Eigen::VectorXd> eligibility;  // Sum of d log pi / d params, when sampling.
  std::vector<FeatureMoments> moments;       // The raw features seen, when normalising.
};

// One learning run's learner objects. Runs share the environment, the feature map, the feature
// options and the policy's shape; their parameters and normalisation may change between calls.
struct Run {
  const FeaturePipeline* features = nullptr;
  LinearPolicy* policy = nullptr;  // The sequential player samples through it.
};

// What every player shares, fixed for the player's life.
struct Setup {
  env::Environment* env = nullptr;
  const features::FeatureMap* map = nullptr;
  std::vector<Run> runs;
  int maxSteps = 0;
  double discount = 1.0;
};

// One episode to play: of which run, from which seed.
struct Task {
  std::size_t run = 0;
  std::uint64_t seed = 0;
};

class Player {
 public:
  virtual ~Player() = default;
  // Plays one episode per task (at most capacity() tasks) with the runs' policies as they are:
  // sampled actions (with eligibilities) or greedy ones. `out` is resized as needed. After an
  // episode that is not ok, a player may skip the later tasks of the same run.
  virtual void play(std::span<const Task> tasks, bool sampling, Records& out) = 0;
  virtual std::size_t capacity() const = 0;
};

// One episode after another, through Environment::step, FeatureMap::evaluate and
// LinearPolicy::sample: the reference.
std::unique_ptr<Player> makeSequentialPlayer(const Setup& setup, std::size_t capacity);
// Side by side; nullptr when the environment has no batched form.
std::unique_ptr<Player> makeLockstepPlayer(const Setup& setup, std::size_t capacity);

// Sizes `out` for n episodes of policies with `parameters` parameters and `rawDim` raw features.
void prepare(Records& out, std::size_t n, Eigen::Index parameters, std::size_t rawDim,
             bool sampling, bool normalising);

}  // namespace gpfd::rl::episodes
