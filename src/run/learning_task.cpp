#include "gpfd/run/learning_task.hpp"

#include <cmath>
#include <limits>

#include "gpfd/jit/compiled_feature_map.hpp"

namespace gpfd::run {
namespace {

constexpr double kWorst = -std::numeric_limits<double>::infinity();

}  // namespace

LearningTask::LearningTask(const ExperimentConfig& config, Budget budget)
    : config_(config), learnerParams_(config.learnerParams) {
  if (budget == Budget::Assessment) {
    for (const auto& [k, v] : config.assessParams) learnerParams_[k] = v;
  }
  const auto environment = env::Registry::global().make(config_.env, config_.envParams);
  stateNames_ = environment->stateNames();
  rl::LearnerRegistry::global().checkSuitable(config_.learner, *environment);
  learner_ = rl::LearnerRegistry::global().make(config_.learner, learnerParams_);
}

rl::LearningCurve LearningTask::train(const features::FeatureMap& map, Rng& rng) const {
  const auto environment = env::Registry::global().make(config_.env, config_.envParams);
  return learner_->train(*environment, map, rng);
}

double LearningTask::score(const rl::LearningCurve& curve) const {
  if (curve.diverged || curve.points.empty()) return kWorst;
  const auto& points = curve.points;
  std::size_t first = 0;
  switch (config_.measure) {
    case TrialMeasure::Final:
      first = points.size() - 1;
      break;
    case TrialMeasure::Mean:
      first = 0;
      break;
    case TrialMeasure::LastFraction: {
      const auto count = static_cast<std::size_t>(
          std::ceil(config_.lastFraction * static_cast<double>(points.size())));
      first = points.size() - std::max<std::size_t>(1, std::min(count, points.size()));
      break;
    }
  }
  double sum = 0.0;
  for (std::size_t i = first; i < points.size(); ++i) sum += points[i].meanReturn;
  const double mean = sum / static_cast<double>(points.size() - first);
  return std::isfinite(mean) ? mean : kWorst;
}

std::shared_ptr<const features::FeatureMap> genomeFeatureMap(const expr::Genome& genome,
                                                             std::size_t stateDim,
                                                             bool withOriginal) {
  auto compiled = std::make_shared<const jit::CompiledFeatureMap>(genome, stateDim);
  if (!withOriginal) return compiled;
  return std::make_shared<const features::ConcatFeatureMap>(
      std::vector<std::shared_ptr<const features::FeatureMap>>{
          compiled, std::make_shared<const features::RawFeatureMap>(stateDim)});
}

double trialFitness(const LearningTask& task, const expr::Genome& genome, Rng& rng) {
  const auto map = genomeFeatureMap(genome, task.stateDim(), task.config().withOriginal);
  const std::uint64_t base = rng();
  double sum = 0.0;
  for (int t = 0; t < task.config().trials; ++t) {
    Rng trialRng(deriveSeed(base, t));
    const double s = task.score(task.train(*map, trialRng));
    if (!std::isfinite(s)) return kWorst;
    sum += s;
  }
  return sum / task.config().trials;
}

}  // namespace gpfd::run
