#include "gpfd/rl/policy_gradient.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "episode_players.hpp"
#include "gpfd/rl/gradient_estimator.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::rl {
namespace {

// Episodes played per call of a player at most (evaluations of many episodes go in chunks).
constexpr std::size_t kMaxLanes = 64;

void checkDimensions(const env::Environment& env, const jit::FeatureMap& map) {
  if (map.inputDim() != env.stateDim()) {
    throw InputError("the feature map reads " + std::to_string(map.inputDim()) +
                         " state variables but " + env.name() + " has " +
                         std::to_string(env.stateDim()),
                     "features");
  }
}

// The learner's objects for one run, and the player that plays its episodes.
struct Learner {
  Learner(env::Environment& env, const jit::FeatureMap& map, const PolicyGradientConfig& config,
          int maxSteps, double discount, std::size_t episodesPerCall)
      : features(map, config.features), policy(env.actionSpace(), features.dim(), config.policy) {
    const episodes::Setup setup{&env, &map, &features, &policy, maxSteps, discount};
    const std::size_t lanes = std::clamp<std::size_t>(episodesPerCall, 1, kMaxLanes);
    if (config.lockstep) player = episodes::makeLockstepPlayer(setup, lanes);
    if (!player) player = episodes::makeSequentialPlayer(setup, lanes);
  }

  // Plays `count` episodes, episode e seeded by seedOf(e), in chunks of the player's capacity;
  // calls use(e, outcome, records, index in records) in episode order, up to and including the
  // first episode that is not ok.
  template <class Seed, class Use>
  void play(int count, bool sampling, Seed&& seedOf, Use&& use) {
    for (int first = 0; first < count;) {
      const int n = std::min<int>(count - first, static_cast<int>(player->capacity()));
      seeds.resize(static_cast<std::size_t>(n));
      for (int e = 0; e < n; ++e) seeds[static_cast<std::size_t>(e)] = seedOf(first + e);
      player->play(seeds, sampling, records);
      for (int e = 0; e < n; ++e) {
        const episodes::Outcome& outcome = records.outcomes[static_cast<std::size_t>(e)];
        use(first + e, outcome, static_cast<std::size_t>(e));
        if (!outcome.ok) return;
      }
      first += n;
    }
  }

  FeaturePipeline features;
  LinearPolicy policy;
  std::unique_ptr<episodes::Player> player;
  std::vector<std::uint64_t> seeds;
  episodes::Records records;
};

void exportWeights(const LinearPolicy& policy, const FeaturePipeline& features,
                   LinearWeights& out) {
  out.rows = policy.outputs();
  out.cols = policy.featureDim();
  out.values.assign(policy.parameters().data(),
                    policy.parameters().data() + policy.parameters().size());
  features.exportTo(out);
}

}  // namespace

LearningCurve trainPolicyGradient(env::Environment& env, const jit::FeatureMap& map,
                                  const PolicyGradientConfig& config, Rng& rng) {
  checkDimensions(env, map);
  if (config.updates < 0 || config.episodesPerUpdate < 1 || config.maxEpisodeSteps < 1) {
    throw InputError("updates >= 0, episodes per update >= 1, max episode steps >= 1 required",
                     "policy gradient");
  }
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t runSeed = rng();
  Learner learner(env, map, config, config.maxEpisodeSteps, config.discount,
                  static_cast<std::size_t>(config.episodesPerUpdate));
  LinearPolicy& policy = learner.policy;
  FeaturePipeline& features = learner.features;
  Rprop rprop(config.rprop, policy.parameterCount());
  EpisodicGradientEstimator estimator(policy.parameterCount(), config.optimalBaseline);
  Eigen::VectorXd gradient(policy.parameterCount());

  LearningCurve curve;
  curve.points.reserve(static_cast<std::size_t>(config.updates) + 1);
  for (int update = 0; update <= config.updates; ++update) {
    estimator.clear();
    double sum = 0.0;
    learner.play(
        config.episodesPerUpdate, true, [&](int e) { return deriveSeed(runSeed, update, e); },
        [&](int, const episodes::Outcome& outcome, std::size_t i) {
          curve.steps += outcome.steps;
          ++curve.episodes;
          if (!outcome.ok) {
            curve.diverged = true;
            curve.divergedReason = "non-finite feature, action, return or likelihood gradient";
            return;
          }
          sum += outcome.undiscounted;
          estimator.addEpisode(learner.records.eligibility[i], outcome.discounted);
          if (config.features.normalise) features.merge(learner.records.moments[i]);
        });
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

Eigen::VectorXd estimatePolicyGradient(env::Environment& env, const jit::FeatureMap& map,
                                       const PolicyGradientConfig& config,
                                       const Eigen::VectorXd& parameters, int episodes, Rng& rng) {
  checkDimensions(env, map);
  const std::uint64_t base = rng();
  Learner learner(env, map, config, config.maxEpisodeSteps, config.discount,
                  static_cast<std::size_t>(std::max(episodes, 1)));
  if (parameters.size() != learner.policy.parameterCount()) {
    throw InputError("wrong number of policy parameters", "policy gradient");
  }
  learner.policy.parameters() = parameters;
  EpisodicGradientEstimator estimator(learner.policy.parameterCount(), config.optimalBaseline);
  bool ok = true;
  learner.play(
      episodes, true, [&](int e) { return deriveSeed(base, e); },
      [&](int, const episodes::Outcome& outcome, std::size_t i) {
        ok = ok && outcome.ok;
        if (ok) estimator.addEpisode(learner.records.eligibility[i], outcome.discounted);
      });
  if (!ok) return {};
  Eigen::VectorXd gradient;
  estimator.gradient(gradient);
  return gradient;
}

EvaluationResult evaluatePolicy(env::Environment& env, const jit::FeatureMap& map,
                                const LinearWeights& weights, const PolicyGradientConfig& config,
                                int episodes, bool greedy, Rng& rng) {
  checkDimensions(env, map);
  const std::uint64_t base = rng();
  Learner learner(env, map, config, config.maxEpisodeSteps, 1.0,
                  static_cast<std::size_t>(std::max(episodes, 1)));
  LinearPolicy& policy = learner.policy;
  if (weights.values.size() != static_cast<std::size_t>(policy.parameterCount())) {
    throw InputError("the weights have " + std::to_string(weights.values.size()) +
                         " values, the policy needs " + std::to_string(policy.parameterCount()),
                     "weights");
  }
  for (std::size_t i = 0; i < weights.values.size(); ++i) {
    policy.parameters()[static_cast<Eigen::Index>(i)] = weights.values[i];
  }
  learner.features.importFrom(weights);
  EvaluationResult result;
  double sum = 0.0, sumSquares = 0.0;
  learner.play(
      episodes, !greedy, [&](int e) { return deriveSeed(base, e); },
      [&](int, const episodes::Outcome& outcome, std::size_t) {
        result.steps += outcome.steps;
        if (!outcome.ok) {
          result.diverged = true;
          return;
        }
        ++result.episodes;
        sum += outcome.undiscounted;
        sumSquares += outcome.undiscounted * outcome.undiscounted;
      });
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
