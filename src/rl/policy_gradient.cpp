#include "gpfd/rl/policy_gradient.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "gpfd/rl/gradient_estimator.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::rl {
namespace {

struct EpisodeOutcome {
  double undiscounted = 0.0;
  double discounted = 0.0;
  std::int64_t steps = 0;
  bool ok = true;  // False: a non-finite state, feature, action or reward.
};

// Buffers of one run, allocated once; the step loop allocates nothing.
struct Workspace {
  std::vector<double> phi, action;
  Eigen::VectorXd eligibility;
};

void checkDimensions(const env::Environment& env, const features::FeatureMap& map) {
  if (map.inputDim() != env.stateDim()) {
    throw InputError("the feature map reads " + std::to_string(map.inputDim()) +
                         " state variables but " + env.name() + " has " +
                         std::to_string(env.stateDim()),
                     "features");
  }
}

// One episode. When `sampling`, the gradient of log pi is summed into ws.eligibility.
EpisodeOutcome runEpisode(env::Environment& env, FeaturePipeline& features, LinearPolicy& policy,
                          Rng& rng, bool sampling, int maxSteps, double discount, Workspace& ws) {
  EpisodeOutcome outcome;
  if (sampling) ws.eligibility.setZero();
  env.reset(rng);
  const std::span<const double> action(ws.action.data(), policy.actionComponents());
  double weight = 1.0;
  for (int t = 0; t < maxSteps; ++t) {
    if (!features.evaluate(env.state().data(), ws.phi.data())) {
      outcome.ok = false;
      return outcome;
    }
    const bool fine =
        sampling ? policy.sample(rng, ws.phi.data(), ws.action.data(), ws.eligibility.data())
                 : policy.greedy(ws.phi.data(), ws.action.data());
    if (!fine) {
      outcome.ok = false;
      return outcome;
    }
    const env::StepResult result = env.step(action);
    ++outcome.steps;
    // A non-finite state is caught here, not by the features: GP's features map it to finite
    // values (ops.hpp), which would hide a broken simulation.
    const auto state = env.state();
    if (!std::isfinite(result.reward) ||
        !std::all_of(state.begin(), state.end(), [](double v) { return std::isfinite(v); })) {
      outcome.ok = false;
      return outcome;
    }
    outcome.undiscounted += result.reward;
    outcome.discounted += weight * result.reward;
    weight *= discount;
    if (result.terminated || result.truncated) break;
  }
  return outcome;
}

void exportWeights(const LinearPolicy& policy, const FeaturePipeline& features,
                   LinearWeights& out) {
  out.rows = policy.outputs();
  out.cols = policy.featureDim();
  out.values.assign(policy.parameters().data(),
                    policy.parameters().data() + policy.parameters().size());
  features.exportTo(out);
}

}  // namespace

LearningCurve trainPolicyGradient(env::Environment& env, const features::FeatureMap& map,
                                  const PolicyGradientConfig& config, Rng& rng) {
  checkDimensions(env, map);
  if (config.updates < 0 || config.episodesPerUpdate < 1 || config.maxEpisodeSteps < 1) {
    throw InputError("updates >= 0, episodes per update >= 1, max episode steps >= 1 required",
                     "policy gradient");
  }
  const auto start = std::chrono::steady_clock::now();
  FeaturePipeline features(map, config.features);
  LinearPolicy policy(env.actionSpace(), features.dim(), config.policy);
  Rprop rprop(config.rprop, policy.parameterCount());
  EpisodicGradientEstimator estimator(policy.parameterCount(), config.optimalBaseline);
  Workspace ws;
  ws.phi.assign(features.dim(), 0.0);
  ws.action.assign(policy.actionComponents(), 0.0);
  ws.eligibility = Eigen::VectorXd::Zero(policy.parameterCount());
  Eigen::VectorXd gradient(policy.parameterCount());

  LearningCurve curve;
  curve.points.reserve(static_cast<std::size_t>(config.updates) + 1);
  for (int update = 0; update <= config.updates; ++update) {
    estimator.clear();
    double sum = 0.0;
    for (int e = 0; e < config.episodesPerUpdate; ++e) {
      const EpisodeOutcome outcome =
          runEpisode(env, features, policy, rng, true, config.maxEpisodeSteps, config.discount, ws);
      curve.steps += outcome.steps;
      ++curve.episodes;
      if (!outcome.ok || !std::isfinite(outcome.discounted) ||
          !std::isfinite(ws.eligibility.sum())) {
        curve.diverged = true;
        curve.divergedReason = "non-finite state, feature, action, return or likelihood gradient";
        break;
      }
      sum += outcome.undiscounted;
      estimator.addEpisode(ws.eligibility, outcome.discounted);
    }
    if (curve.diverged) break;
    curve.points.push_back(
        {update, curve.episodes, curve.steps, sum / static_cast<double>(config.episodesPerUpdate)});
    exportWeights(policy, features, curve.weights);
    if (config.onPoint) config.onPoint(curve.points.back());
    if (update == config.updates) break;
    if (config.maxTotalSteps > 0 && curve.steps >= config.maxTotalSteps) break;
    estimator.gradient(gradient);
    if (!gradient.allFinite()) {
      curve.diverged = true;
      curve.divergedReason = "non-finite gradient estimate";
      break;
    }
    rprop.step(gradient, policy.parameters());
    policy.clampParameters();
    features.refresh(policy.parameters().data(), policy.outputs());
    if (!policy.parameters().allFinite()) {
      curve.diverged = true;
      curve.divergedReason = "non-finite policy weights";
      break;
    }
  }
  curve.wallSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return curve;
}

Eigen::VectorXd estimatePolicyGradient(env::Environment& env, const features::FeatureMap& map,
                                       const PolicyGradientConfig& config,
                                       const Eigen::VectorXd& parameters, int episodes, Rng& rng) {
  checkDimensions(env, map);
  FeaturePipeline features(map, config.features);
  LinearPolicy policy(env.actionSpace(), features.dim(), config.policy);
  if (parameters.size() != policy.parameterCount()) {
    throw InputError("wrong number of policy parameters", "policy gradient");
  }
  policy.parameters() = parameters;
  EpisodicGradientEstimator estimator(policy.parameterCount(), config.optimalBaseline);
  Workspace ws;
  ws.phi.assign(features.dim(), 0.0);
  ws.action.assign(policy.actionComponents(), 0.0);
  ws.eligibility = Eigen::VectorXd::Zero(policy.parameterCount());
  for (int e = 0; e < episodes; ++e) {
    const EpisodeOutcome outcome =
        runEpisode(env, features, policy, rng, true, config.maxEpisodeSteps, config.discount, ws);
    if (!outcome.ok || !std::isfinite(outcome.discounted)) return {};
    estimator.addEpisode(ws.eligibility, outcome.discounted);
  }
  Eigen::VectorXd gradient;
  estimator.gradient(gradient);
  return gradient;
}

EvaluationResult evaluatePolicy(env::Environment& env, const features::FeatureMap& map,
                                const LinearWeights& weights, const PolicyGradientConfig& config,
                                int episodes, bool greedy, Rng& rng) {
  checkDimensions(env, map);
  FeaturePipeline features(map, config.features);
  LinearPolicy policy(env.actionSpace(), features.dim(), config.policy);
  if (weights.values.size() != static_cast<std::size_t>(policy.parameterCount())) {
    throw InputError("the weights have " + std::to_string(weights.values.size()) +
                         " values, the policy needs " + std::to_string(policy.parameterCount()),
                     "weights");
  }
  for (std::size_t i = 0; i < weights.values.size(); ++i) {
    policy.parameters()[static_cast<Eigen::Index>(i)] = weights.values[i];
  }
  features.importFrom(weights);
  Workspace ws;
  ws.phi.assign(features.dim(), 0.0);
  ws.action.assign(policy.actionComponents(), 0.0);
  ws.eligibility = Eigen::VectorXd::Zero(policy.parameterCount());
  EvaluationResult result;
  double sum = 0.0, sumSquares = 0.0;
  for (int e = 0; e < episodes; ++e) {
    const EpisodeOutcome outcome =
        runEpisode(env, features, policy, rng, !greedy, config.maxEpisodeSteps, 1.0, ws);
    result.steps += outcome.steps;
    if (!outcome.ok) {
      result.diverged = true;
      break;
    }
    ++result.episodes;
    sum += outcome.undiscounted;
    sumSquares += outcome.undiscounted * outcome.undiscounted;
  }
  if (result.episodes > 0) {
    const double n = static_cast<double>(result.episodes);
    result.meanReturn = sum / n;
    result.stdReturn = result.episodes > 1
                           ? std::sqrt(std::max(0.0, (sumSquares - sum * sum / n) / (n - 1)))
                           : 0.0;
  }
  return result;
}

}  // namespace gpfd::rl
