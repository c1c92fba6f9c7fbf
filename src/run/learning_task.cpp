#include "gpfd/run/learning_task.hpp"

#include <cmath>
#include <limits>

#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/run/redundancy.hpp"

namespace gpfd::run {
namespace {

constexpr double kWorst = -std::numeric_limits<double>::infinity();
constexpr std::uint64_t kStateSampleStream = 0x5a3;

}  // namespace

LearningTask::LearningTask(const ExperimentConfig& config, Budget budget)
    : config_(config),
      budget_(budget),
      measure_(config.measure),
      learnerParams_(config.learnerParams) {
  const std::map<std::string, std::string>* overrides = nullptr;
  if (budget == Budget::Assessment) overrides = &config.assessParams;
  if (budget == Budget::Validation) {
    overrides = &config.validation.params;
    measure_ = config.validation.measure.value_or(config.measure);
  }
  if (budget == Budget::Confirmation) {
    overrides = &config.validation.confirmParams;
    measure_ = config.validation.confirmMeasure;
  }
  if (overrides != nullptr) {
    for (const auto& [k, v] : *overrides) learnerParams_[k] = v;
  }
  const auto environment = env::Registry::global().make(config_.env, config_.envParams);
  stateNames_ = environment->stateNames();
  rl::LearnerRegistry::global().checkSuitable(config_.learner, *environment);
  learner_ = rl::LearnerRegistry::global().make(config_.learner, learnerParams_);
  if (config_.dropRedundant || config_.normalise || config_.rejectConstant) {
    sample_ = std::make_shared<const FeatureSample>(
        sampleVisitedStates(*environment, static_cast<std::size_t>(config_.stateSample),
                            deriveSeed(config_.seed, kStateSampleStream)),
        stateDim());
  }
}

expr::Genome LearningTask::prepared(const expr::Genome& genome) const {
  // Placeholders fill min_features for the GP only (run/redundancy.hpp).
  const auto seen = config_.withOriginal ? withoutPlaceholders(genome) : genome;
  return config_.normalise ? normaliseFeatures(seen, *sample_) : seen;
}

std::shared_ptr<const features::FeatureMap> LearningTask::featureMap(
    const expr::Genome& genome) const {
  return genomeFeatureMap(prepared(genome), stateDim(), config_.withOriginal);
}

rl::LearningCurve LearningTask::train(const features::FeatureMap& map, Rng& rng) const {
  const auto environment = env::Registry::global().make(config_.env, config_.envParams);
  return learner_->train(*environment, map, rng);
}

std::vector<rl::LearningCurve> LearningTask::trainRuns(const features::FeatureMap& map,
                                                       std::span<Rng> rngs) const {
  return learner_->trainRuns(
      [this] { return env::Registry::global().make(config_.env, config_.envParams); }, map, rngs);
}

std::vector<double> LearningTask::scores(const std::vector<rl::LearningCurve>& curves) const {
  std::vector<double> out;
  for (const auto& curve : curves) out.push_back(score(curve));
  return out;
}

double LearningTask::score(const rl::LearningCurve& curve) const {
  if (curve.diverged || curve.points.empty()) return kWorst;
  const auto& points = curve.points;
  std::size_t first = 0;
  switch (measure_) {
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

namespace {

// Whether the genome's features are the state variables themselves, in order.
bool isIdentity(const expr::Genome& genome, std::size_t stateDim) {
  if (genome.featureCount() != stateDim || genome.size() != stateDim) return false;
  for (std::size_t i = 0; i < stateDim; ++i) {
    const auto& node = genome.nodes()[i];
    if (node.op != expr::Op::Var || node.var != i) return false;
  }
  return true;
}

}  // namespace

std::shared_ptr<const features::FeatureMap> genomeFeatureMap(const expr::Genome& genome,
                                                             std::size_t stateDim,
                                                             bool withOriginal) {
  if (!withOriginal) return std::make_shared<const jit::CompiledFeatureMap>(genome, stateDim);
  // The original variables added to themselves would only repeat every column; placeholders
  // (run/redundancy.hpp) stand for no feature.
  const auto added = withoutPlaceholders(genome);
  if (added.featureCount() == 0 || isIdentity(added, stateDim)) {
    return std::make_shared<const features::RawFeatureMap>(stateDim);
  }
  return std::make_shared<const features::ConcatFeatureMap>(
      std::vector<std::shared_ptr<const features::FeatureMap>>{
          std::make_shared<const jit::CompiledFeatureMap>(added, stateDim),
          std::make_shared<const features::RawFeatureMap>(stateDim)});
}

double trialFitness(const LearningTask& task, const expr::Genome& genome, Rng& rng) {
  const auto map = task.featureMap(genome);
  const std::uint64_t base = rng();
  std::vector<Rng> trialRngs;
  for (int t = 0; t < task.config().trials; ++t) trialRngs.emplace_back(deriveSeed(base, t));
  double sum = 0.0;
  for (const auto& curve : task.trainRuns(*map, trialRngs)) {
    const double s = task.score(curve);
    if (!std::isfinite(s)) return kWorst;
    sum += s;
  }
  return sum / task.config().trials;
}

std::vector<ExperimentConfig> fitnessRungs(const ExperimentConfig& config) {
  std::vector<ExperimentConfig> rungs;
  if (!(config.gp.promote > 0)) return rungs;
  const auto rung = [&config](const std::map<std::string, std::string>& overrides,
                              TrialMeasure measure) {
    ExperimentConfig c = config;
    for (const auto& [key, value] : overrides) c.learnerParams[key] = value;
    c.measure = measure;
    c.gp.promote = 0.0;
    c.rungParams.clear();
    return c;
  };
  if (!config.rungParams.empty()) rungs.push_back(rung(config.rungParams, config.measure));
  rungs.push_back(rung(config.validation.confirmParams, config.validation.confirmMeasure));
  return rungs;
}

}  // namespace gpfd::run
