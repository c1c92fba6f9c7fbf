// rl: Augmented Random Search (ars.hpp; Mania, Guy & Recht 2018, Algorithm 2). The 2N episodes of
// an iteration, of every run trained together, are one call of an episode player
// (episode_players.hpp): each episode is a "run" of the player with its own perturbed weights,
// played greedily (the arg-max of the scores, or the mean action that the environment clips),
// side by side in lockstep or one after another, with the same results.
#include "gpfd/rl/ars.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>

#include "episode_players.hpp"
#include "gpfd/rl/linear_policy.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/ziggurat.hpp"

namespace gpfd::rl {
namespace {

constexpr std::size_t kMaxLanes = 128;  // Episodes per call of a player at most.
// Streams of a run's seed besides its episodes': the directions of each iteration, the start.
constexpr std::uint64_t kDirectionStream = 0x415253;
constexpr std::uint64_t kStartStream = 0x41525331;

void checkSettings(const env::Environment& env, const features::FeatureMap& map,
                   const ArsConfig& config) {
  if (map.inputDim() != env.stateDim()) {
    throw InputError("the feature map reads " + std::to_string(map.inputDim()) +
                         " state variables but " + env.name() + " has " +
                         std::to_string(env.stateDim()),
                     "features");
  }
  arsParams().check(config);
  if (config.updates < 0 || config.directions < 1 || config.maxEpisodeSteps < 1 ||
      !(config.deltaStd > 0.0) || !(config.learningRate >= 0.0)) {
    throw InputError(
        "updates >= 0, n_delta >= 1, max_episode_steps >= 1, delta_std > 0 and "
        "learning_rate >= 0 required",
        "ars");
  }
}

// One run: the weights, the 2N policies an iteration plays (slot 2k: theta + nu delta_k, slot
// 2k + 1: theta - nu delta_k), and what V2 has seen.
struct ArsRun {
  ArsRun(env::Environment& env, const features::FeatureMap& map, const ArsConfig& config)
      : features(map, config.features),
        theta(env.actionSpace(), features.dim(), {}),
        seen(features.rawDim()) {
    const auto slots = static_cast<std::size_t>(2 * config.directions);
    policies.reserve(slots);  // The player keeps pointers to them.
    for (std::size_t e = 0; e < slots; ++e) {
      policies.emplace_back(env.actionSpace(), features.dim(), PolicyOptions{});
    }
    deltas.assign(static_cast<std::size_t>(config.directions),
                  Eigen::VectorXd::Zero(theta.parameterCount()));
    plus.assign(deltas.size(), 0.0);
    minus.assign(deltas.size(), 0.0);
  }

  FeaturePipeline features;
  LinearPolicy theta;
  std::vector<LinearPolicy> policies;
  std::vector<Eigen::VectorXd> deltas;
  std::vector<double> plus, minus;  // The returns of the current iteration per direction.
  FeatureMoments seen;              // Every raw feature row of the iterations played (V2).
  LearningCurve curve;
  std::uint64_t seed = 0;
  bool learning = true;
  double sum = 0.0;  // Of the current row's returns.
};

void exportWeights(const ArsRun& run, LinearWeights& out) {
  out.rows = run.theta.outputs();
  out.cols = run.theta.featureDim();
  const Eigen::VectorXd& w = run.theta.parameters();
  out.values.assign(w.data(), w.data() + w.size());
  run.features.exportTo(out);
}

// zero_policy = false: uniform in [-1/sqrt(d), 1/sqrt(d)], d the features without the bias (a
// linear layer's fan-in), from the run's own stream.
void randomStart(ArsRun& run) {
  Rng rng(deriveSeed(run.seed, kStartStream));
  const auto fanIn = std::max<std::size_t>(run.features.rawDim(), 1);
  const double bound = 1.0 / std::sqrt(static_cast<double>(fanIn));
  for (double& w : run.theta.parameters()) w = rng.uniform(-bound, bound);
}

// The policies of row `update`: around theta along fresh directions, or theta itself.
void perturb(ArsRun& run, int update, double deltaStd, bool unperturbed) {
  const Eigen::VectorXd& theta = run.theta.parameters();
  if (unperturbed) {
    for (auto& policy : run.policies) policy.parameters() = theta;
    return;
  }
  Rng rng(deriveSeed(run.seed, kDirectionStream, update));
  for (std::size_t k = 0; k < run.deltas.size(); ++k) {
    for (double& d : run.deltas[k]) d = standardNormal(rng);
    run.policies[2 * k].parameters() = theta + deltaStd * run.deltas[k];
    run.policies[2 * k + 1].parameters() = theta - deltaStd * run.deltas[k];
  }
}

// V2: the normalisation of the next iteration, mean and standard deviation of all rows seen (1
// where there are fewer than two rows or the deviation is about 0). The weights are not
// re-expressed (the paper's V2).
void refreshNormalisation(ArsRun& run) {
  const FeatureMoments& m = run.seen;
  LinearWeights stats;
  stats.shift = m.mean;
  stats.scale.assign(m.mean.size(), 1.0);
  for (std::size_t j = 0; j < m.mean.size() && m.count > 1; ++j) {
    const double sd = std::sqrt(m.m2[j] / static_cast<double>(m.count - 1));
    if (std::isfinite(sd) && sd > 1e-12) stats.scale[j] = sd;
  }
  run.features.importFrom(stats);
}

// After row `update` was played: the row, then the step (or the end of the run).
void finishRow(ArsRun& run, std::size_t index, int update, const ArsConfig& config) {
  LearningCurve& curve = run.curve;
  if (curve.diverged) {
    run.learning = false;
    return;
  }
  curve.points.push_back(
      {update, curve.episodes, curve.steps, run.sum / static_cast<double>(2 * config.directions)});
  exportWeights(run, curve.weights);
  if (config.onPoint) config.onPoint(curve.points.back());
  if (config.onRunPoint) config.onRunPoint(index, curve.points.back());
  if (update == config.updates ||
      (config.maxTotalSteps > 0 && curve.steps >= config.maxTotalSteps)) {
    run.learning = false;
    return;
  }
  arsStep(run.plus, run.minus, run.deltas, config.top(), config.learningRate,
          run.theta.parameters());
  if (!run.theta.parameters().allFinite()) {
    curve.diverged = true;
    curve.divergedReason = "non-finite policy weights";
    run.learning = false;
    return;
  }
  if (config.features.normalise) refreshNormalisation(run);
}

}  // namespace

void arsStep(std::span<const double> plus, std::span<const double> minus,
             std::span<const Eigen::VectorXd> deltas, int top, double learningRate,
             Eigen::VectorXd& theta) {
  std::vector<std::size_t> order(deltas.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::max(plus[a], minus[a]) > std::max(plus[b], minus[b]);
  });
  order.resize(std::min(order.size(), static_cast<std::size_t>(std::max(top, 1))));
  const double n = 2.0 * static_cast<double>(order.size());
  double mean = 0.0;
  for (const std::size_t k : order) mean += plus[k] + minus[k];
  mean /= n;
  double squares = 0.0;
  for (const std::size_t k : order) {
    squares += (plus[k] - mean) * (plus[k] - mean) + (minus[k] - mean) * (minus[k] - mean);
  }
  const double sigma = std::sqrt(squares / n);
  if (!(sigma > 0.0)) return;
  Eigen::VectorXd step = Eigen::VectorXd::Zero(theta.size());
  for (const std::size_t k : order) step += (plus[k] - minus[k]) * deltas[k];
  theta += (learningRate / (static_cast<double>(order.size()) * sigma)) * step;
}

std::vector<LearningCurve> trainArsRuns(env::Environment& env, const features::FeatureMap& map,
                                        const ArsConfig& config, std::span<Rng> rngs) {
  checkSettings(env, map, config);
  const auto start = std::chrono::steady_clock::now();
  const auto slots = static_cast<std::size_t>(2 * config.directions);
  std::vector<std::unique_ptr<ArsRun>> runs;
  episodes::Setup setup{&env, &map, {}, config.maxEpisodeSteps, 1.0};
  for (std::size_t k = 0; k < rngs.size(); ++k) {
    runs.push_back(std::make_unique<ArsRun>(env, map, config));
    ArsRun& run = *runs.back();
    run.seed = rngs[k]();
    if (!config.zeroPolicy) randomStart(run);
    run.curve.points.reserve(static_cast<std::size_t>(config.updates) + 1);
    for (auto& policy : run.policies) setup.runs.push_back({&run.features, &policy});
  }
  const std::size_t lanes = std::clamp<std::size_t>(runs.size() * slots, 1, kMaxLanes);
  std::unique_ptr<episodes::Player> player;
  if (config.lockstep) player = episodes::makeLockstepPlayer(setup, lanes);
  if (!player) player = episodes::makeSequentialPlayer(setup, lanes);
  std::vector<episodes::Task> tasks;
  episodes::Records records;
  for (int update = 0; update <= config.updates; ++update) {
    const bool unperturbed = config.greedyLastRow && update == config.updates;
    tasks.clear();
    for (std::size_t r = 0; r < runs.size(); ++r) {
      ArsRun& run = *runs[r];
      if (!run.learning) continue;
      run.sum = 0.0;
      perturb(run, update, config.deltaStd, unperturbed);
      for (std::size_t e = 0; e < slots; ++e) {
        tasks.push_back({r * slots + e, deriveSeed(run.seed, update, unperturbed ? e : e / 2)});
      }
    }
    if (tasks.empty()) break;
    for (std::size_t first = 0; first < tasks.size(); first += player->capacity()) {
      const std::size_t n = std::min(tasks.size() - first, player->capacity());
      player->play(std::span(tasks.data() + first, n), false, records);
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t slot = tasks[first + i].run;
        ArsRun& run = *runs[slot / slots];
        if (run.curve.diverged) continue;
        const episodes::Outcome& outcome = records.outcomes[i];
        run.curve.steps += outcome.steps;
        ++run.curve.episodes;
        if (!outcome.ok) {  // finishRow then ends the run.
          run.curve.diverged = true;
          run.curve.divergedReason = "non-finite state, feature, action or reward";
          continue;
        }
        run.sum += outcome.undiscounted;
        const std::size_t e = slot % slots;
        (e % 2 == 0 ? run.plus : run.minus)[e / 2] = outcome.undiscounted;
        if (config.features.normalise) run.seen.merge(records.moments[i]);
      }
    }
    for (std::size_t r = 0; r < runs.size(); ++r) {
      if (runs[r]->learning) finishRow(*runs[r], r, update, config);
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<LearningCurve> curves;
  for (auto& run : runs) {
    run->curve.wallSeconds = seconds / static_cast<double>(runs.size());
    curves.push_back(std::move(run->curve));
  }
  return curves;
}

LearningCurve trainArs(env::Environment& env, const features::FeatureMap& map,
                       const ArsConfig& config, Rng& rng) {
  return std::move(trainArsRuns(env, map, config, std::span<Rng>(&rng, 1)).front());
}

}  // namespace gpfd::rl
