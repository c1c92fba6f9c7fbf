// rl: policy gradient with Rprop (Girgin & Preux, section 4): a linear policy, the episodic
// likelihood-ratio gradient with the optimal baseline, an Rprop step every few episodes; or, in
// place of Rprop, the episodic natural actor-critic's step of a fixed KL divergence
// (natural_gradient.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/features.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/rl/linear_policy.hpp"
#include "gpfd/rl/rprop.hpp"
#include "gpfd/util/params.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::rl {

// How an update moves the weights: Rprop on the signs of the gradient (the paper's), or a step
// along the natural gradient whose size is a KL divergence (natural_gradient.hpp).
enum class StepRule { Rprop, Natural };

struct PolicyGradientConfig {
  int updates = 100;           // Policy updates; the curve has updates + 1 rows.
  int episodesPerUpdate = 10;  // Paper: 10.
  // Steps per episode at most, on top of the environment's own time limit (a safety cap).
  int maxEpisodeSteps = 100000;
  // Stop after the batch in which the total number of steps reaches this (0: no cap).
  std::int64_t maxTotalSteps = 0;
  double discount = 1.0;        // gamma for the return in the gradient (the curve is undiscounted).
  bool optimalBaseline = true;  // Peters & Schaal's baseline; false: no baseline.
  StepRule step = StepRule::Rprop;
  RpropConfig rprop = RpropConfig::paperLarge();
  double naturalKl = 0.01;  // StepRule::Natural: the mean KL divergence per step of an update.
  PolicyOptions policy;
  FeatureOptions features;
  // Each episode draws its start state and actions from its own stream, seeded from the run's
  // seed, the update and the episode. Lockstep (default): the episodes of an update run side by
  // side through the environment's batched form (env/batch.hpp), or where it has none through
  // copies of it stepped lane by lane (env::makeLaneByLaneBatch; an environment that cannot be
  // copied plays sequentially); when false, one after another (the reference). Both give the
  // same results, given that an episode depends only on the parameters, the Rng that reset()
  // draws from and the actions (the Environment contract).
  bool lockstep = true;
  // The curve's last row (the batch after the last update, which trains nothing) plays the final
  // weights without exploration: the mean action, or the most likely choice. Its level is then
  // the learned policy's own, free of the exploration noise that the other rows carry. A run that
  // maxTotalSteps ends early ends on a sampled row.
  bool greedyLastRow = false;
  // Called with each row of the curve as soon as it is complete (progress output); may be empty.
  std::function<void(const CurvePoint&)> onPoint;
  // The same with the run's index (trainPolicyGradientRuns; 0 for a single run); may be empty.
  RunPointCallback onRunPoint;
};

// The learner's parameters ("pg": gpfd learners lists them): names, ranges, defaults, meanings.
const ParamTable<PolicyGradientConfig>& policyGradientParams();

// Trains from zero weights, drawing one value from `rng` (the run's seed). The map's inputDim()
// must equal env.stateDim() (InputError otherwise). Row u of the curve is the batch played with the
// policy after u updates; the final weights are those of the last row. A non-finite feature, action
// or return marks the curve diverged and ends it; nothing throws for numerical trouble.
LearningCurve trainPolicyGradient(env::Environment& env, const features::FeatureMap& map,
                                  const PolicyGradientConfig& config, Rng& rng);

// Several independent runs, one per engine: run k gives exactly trainPolicyGradient(env, map,
// config, rngs[k]). With config.lockstep the episodes of each update of every run still learning
// are played side by side (runs x episodesPerUpdate lanes), which fills the lanes better than one
// run alone: the K trials of a fitness evaluation. config.onPoint sees every run's rows, update by
// update (config.onRunPoint with the run's index); a curve's wallSeconds is its share of the whole
// time.
std::vector<LearningCurve> trainPolicyGradientRuns(env::Environment& env,
                                                   const features::FeatureMap& map,
                                                   const PolicyGradientConfig& config,
                                                   std::span<Rng> rngs);

// The gradient estimate (the one an update would use) at the given policy parameters, from
// `episodes` sampled episodes: for tests and diagnostics. Empty when a run diverged.
Eigen::VectorXd estimatePolicyGradient(env::Environment& env, const features::FeatureMap& map,
                                       const PolicyGradientConfig& config,
                                       const Eigen::VectorXd& parameters, int episodes, Rng& rng);

struct EvaluationResult {
  int episodes = 0;
  double meanReturn = 0.0;
  double stdReturn = 0.0;  // Sample standard deviation of the episode returns.
  std::int64_t steps = 0;
  bool diverged = false;
};

// Plays `episodes` episodes with given weights (as trainPolicyGradient returns them, with the
// same config.policy and config.features), greedy (the mean action / most probable choice) or
// stochastic.
EvaluationResult evaluatePolicy(env::Environment& env, const features::FeatureMap& map,
                                const LinearWeights& weights, const PolicyGradientConfig& config,
                                int episodes, bool greedy, Rng& rng);

// The registry entry "pg": every field of PolicyGradientConfig as a parameter, on environments
// whose actions are a box or one discrete choice.
LearnerInfo policyGradientLearner();

}  // namespace gpfd::rl
