#include "gpfd/rl/policy_gradient.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "episode_players.hpp"
#include "gpfd/rl/gradient_estimator.hpp"
#include "gpfd/rl/natural_gradient.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::rl {
namespace {

// Episodes played per call of a player at most (evaluations of many episodes go in chunks).
constexpr std::size_t kMaxLanes = 64;

void checkDimensions(const env::Environment& env, const features::FeatureMap& map) {
  if (map.inputDim() != env.stateDim()) {
    throw InputError("the feature map reads " + std::to_string(map.inputDim()) +
                         " state variables but " + env.name() + " has " +
                         std::to_string(env.stateDim()),
                     "features");
  }
}

// The learner's objects for one run.
struct RunState {
  RunState(env::Environment& env, const features::FeatureMap& map,
           const PolicyGradientConfig& config)
      : features(map, config.features),
        policy(env.actionSpace(), features.dim(), config.policy),
        rprop(config.rprop, policy.parameterCount()),
        estimator(policy.parameterCount(), config.optimalBaseline),
        natural(config.step == StepRule::Natural ? policy.parameterCount() : 0),
        gradient(policy.parameterCount()) {}

  FeaturePipeline features;
  LinearPolicy policy;
  Rprop rprop;
  EpisodicGradientEstimator estimator;
  NaturalGradientStep natural;  // Sized 0 unless StepRule::Natural.
  Eigen::VectorXd gradient;
  LearningCurve curve;
  std::uint64_t seed = 0;
  bool learning = true;  // Still playing updates.
  bool failed = false;   // An episode of the current batch was not ok.
  double sum = 0.0;      // Of the current batch's returns.
};

// Runs, the player of their episodes, and the task list: the episodes to play, in run order and
// episode order within a run.
struct Learners {
  Learners(env::Environment& env, const features::FeatureMap& map,
           const PolicyGradientConfig& config, std::size_t count, int maxSteps, double discount,
           std::size_t episodesPerCall) {
    episodes::Setup setup{&env, &map, {}, maxSteps, discount};
    for (std::size_t k = 0; k < count; ++k) {
      runs.push_back(std::make_unique<RunState>(env, map, config));
      setup.runs.push_back({&runs.back()->features, &runs.back()->policy});
    }
    const std::size_t lanes = std::clamp<std::size_t>(episodesPerCall, 1, kMaxLanes);
    if (config.lockstep) player = episodes::makeLockstepPlayer(setup, lanes);
    if (!player) player = episodes::makeSequentialPlayer(setup, lanes);
  }

  // Plays `tasks` in chunks of the player's capacity; calls use(task, outcome, index in records)
  // in task order, skipping the tasks of a run after its first episode that is not ok.
  template <class Use>
  void play(bool sampling, Use&& use) {
    std::vector<std::uint8_t> failed(runs.size(), 0);
    for (std::size_t first = 0; first < tasks.size(); first += player->capacity()) {
      const std::size_t n = std::min(tasks.size() - first, player->capacity());
      const std::span<const episodes::Task> chunk(tasks.data() + first, n);
      player->play(chunk, sampling, records);
      for (std::size_t i = 0; i < n; ++i) {
        if (failed[chunk[i].run]) continue;
        use(chunk[i], records.outcomes[i], i);
        if (!records.outcomes[i].ok) failed[chunk[i].run] = 1;
      }
    }
  }

  std::vector<std::unique_ptr<RunState>> runs;
  std::unique_ptr<episodes::Player> player;
  std::vector<episodes::Task> tasks;
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

// After a batch: the run's row of the curve, then its update (or its end).
void finishBatch(RunState& run, std::size_t index, int update, const PolicyGradientConfig& config) {
  LearningCurve& curve = run.curve;
  if (curve.diverged) {
    run.learning = false;
    return;
  }
  curve.points.push_back({update, curve.episodes, curve.steps,
                          run.sum / static_cast<double>(config.episodesPerUpdate)});
  exportWeights(run.policy, run.features, curve.weights);
  if (config.onPoint) config.onPoint(curve.points.back());
  if (config.onRunPoint) config.onRunPoint(index, curve.points.back());
  if (update == config.updates ||
      (config.maxTotalSteps > 0 && curve.steps >= config.maxTotalSteps)) {
    run.learning = false;
    return;
  }
  if (config.step == StepRule::Natural) {
    run.natural.step(config.naturalKl, run.gradient);
  } else {
    run.estimator.gradient(run.gradient);
  }
  if (!run.gradient.allFinite()) {
    curve.diverged = true;
    curve.divergedReason = "non-finite gradient estimate";
    run.learning = false;
    return;
  }
  if (config.step == StepRule::Natural) {
    run.policy.parameters() += run.gradient;
  } else {
    run.rprop.step(run.gradient, run.policy.parameters());
  }
  run.policy.clampParameters();
  run.features.refresh(run.policy.parameters().data(), run.policy.outputs());
  if (!run.policy.parameters().allFinite()) {
    curve.diverged = true;
    curve.divergedReason = "non-finite policy weights";
    run.learning = false;
  }
}

}  // namespace

std::vector<LearningCurve> trainPolicyGradientRuns(env::Environment& env,
                                                   const features::FeatureMap& map,
                                                   const PolicyGradientConfig& config,
                                                   std::span<Rng> rngs) {
  checkDimensions(env, map);
  if (config.updates < 0 || config.episodesPerUpdate < 1 || config.maxEpisodeSteps < 1) {
    throw InputError("updates >= 0, episodes per update >= 1, max episode steps >= 1 required",
                     "policy gradient");
  }
  const auto start = std::chrono::steady_clock::now();
  const auto episodesPerUpdate = static_cast<std::size_t>(config.episodesPerUpdate);
  Learners learners(env, map, config, rngs.size(), config.maxEpisodeSteps, config.discount,
                    rngs.size() * episodesPerUpdate);
  for (std::size_t k = 0; k < rngs.size(); ++k) {
    learners.runs[k]->seed = rngs[k]();
    learners.runs[k]->curve.points.reserve(static_cast<std::size_t>(config.updates) + 1);
  }
  for (int update = 0; update <= config.updates; ++update) {
    learners.tasks.clear();
    for (std::size_t k = 0; k < learners.runs.size(); ++k) {
      RunState& run = *learners.runs[k];
      if (!run.learning) continue;
      run.estimator.clear();
      run.natural.clear();
      run.sum = 0.0;
      for (int e = 0; e < config.episodesPerUpdate; ++e) {
        learners.tasks.push_back({k, deriveSeed(run.seed, update, e)});
      }
    }
    if (learners.tasks.empty()) break;
    const bool sampling = !(config.greedyLastRow && update == config.updates);
    learners.play(sampling, [&](const episodes::Task& task, const episodes::Outcome& outcome,
                                std::size_t i) {
      RunState& run = *learners.runs[task.run];
      run.curve.steps += outcome.steps;
      ++run.curve.episodes;
      if (!outcome.ok) {
        run.curve.diverged = true;
        run.curve.divergedReason =
            "non-finite state, feature, action, return or likelihood gradient";
        return;
      }
      run.sum += outcome.undiscounted;
      if (sampling && config.step == StepRule::Natural) {
        run.natural.addEpisode(learners.records.eligibility[i], outcome.discounted, outcome.steps);
      } else if (sampling) {
        run.estimator.addEpisode(learners.records.eligibility[i], outcome.discounted);
      }
      if (config.features.normalise) run.features.merge(learners.records.moments[i]);
    });
    for (std::size_t k = 0; k < learners.runs.size(); ++k) {
      if (learners.runs[k]->learning) finishBatch(*learners.runs[k], k, update, config);
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<LearningCurve> curves;
  for (auto& run : learners.runs) {
    run->curve.wallSeconds = seconds / static_cast<double>(learners.runs.size());
    curves.push_back(std::move(run->curve));
  }
  return curves;
}

LearningCurve trainPolicyGradient(env::Environment& env, const features::FeatureMap& map,
                                  const PolicyGradientConfig& config, Rng& rng) {
  return std::move(trainPolicyGradientRuns(env, map, config, std::span<Rng>(&rng, 1)).front());
}

Eigen::VectorXd estimatePolicyGradient(env::Environment& env, const features::FeatureMap& map,
                                       const PolicyGradientConfig& config,
                                       const Eigen::VectorXd& parameters, int episodes, Rng& rng) {
  checkDimensions(env, map);
  const std::uint64_t base = rng();
  Learners learners(env, map, config, 1, config.maxEpisodeSteps, config.discount,
                    static_cast<std::size_t>(std::max(episodes, 1)));
  RunState& run = *learners.runs.front();
  if (parameters.size() != run.policy.parameterCount()) {
    throw InputError("wrong number of policy parameters", "policy gradient");
  }
  run.policy.parameters() = parameters;
  for (int e = 0; e < episodes; ++e) learners.tasks.push_back({0, deriveSeed(base, e)});
  bool ok = true;
  learners.play(true, [&](const episodes::Task&, const episodes::Outcome& outcome, std::size_t i) {
    ok = ok && outcome.ok;
    if (ok) run.estimator.addEpisode(learners.records.eligibility[i], outcome.discounted);
  });
  if (!ok) return {};
  Eigen::VectorXd gradient;
  run.estimator.gradient(gradient);
  return gradient;
}

EvaluationResult evaluatePolicy(env::Environment& env, const features::FeatureMap& map,
                                const LinearWeights& weights, const PolicyGradientConfig& config,
                                int episodes, bool greedy, Rng& rng) {
  checkDimensions(env, map);
  const std::uint64_t base = rng();
  Learners learners(env, map, config, 1, config.maxEpisodeSteps, 1.0,
                    static_cast<std::size_t>(std::max(episodes, 1)));
  RunState& run = *learners.runs.front();
  if (weights.values.size() != static_cast<std::size_t>(run.policy.parameterCount())) {
    throw InputError("the weights have " + std::to_string(weights.values.size()) +
                         " values, the policy needs " + std::to_string(run.policy.parameterCount()),
                     "weights");
  }
  for (std::size_t i = 0; i < weights.values.size(); ++i) {
    run.policy.parameters()[static_cast<Eigen::Index>(i)] = weights.values[i];
  }
  run.features.importFrom(weights);
  for (int e = 0; e < episodes; ++e) learners.tasks.push_back({0, deriveSeed(base, e)});
  EvaluationResult result;
  double sum = 0.0, sumSquares = 0.0;
  learners.play(!greedy, [&](const episodes::Task&, const episodes::Outcome& outcome, std::size_t) {
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
