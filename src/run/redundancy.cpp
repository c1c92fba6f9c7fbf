#include "gpfd/run/redundancy.hpp"

#include <Eigen/Core>
#include <cmath>

#include "gpfd/run/experiment_config.hpp"
#include "gpfd/run/learning_task.hpp"

namespace gpfd::run {
namespace {

// An orthonormal basis grown one column at a time (Gram-Schmidt, applied twice for accuracy:
// "twice is enough", Giraud et al. 2005).
class Span {
 public:
  explicit Span(std::size_t rows) : rows_(rows) {}

  // Adds `values` unless it lies in the span, or (when the span holds the constant 1 first) the
  // span explains at least `explained` of its variance; returns whether it was added.
  bool add(const std::vector<double>& values, double explained = 1.0) {
    Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(values.data(), values.size());
    const double scale = v.cwiseAbs().maxCoeff();
    if (!(scale > 0) || !std::isfinite(scale)) return false;  // Zero is in every span.
    v /= scale;  // Saturated values (DBL_MAX) would overflow the norms.
    const double norm = v.norm();
    const double centred = (v.array() - v.mean()).matrix().norm();
    for (int pass = 0; pass < 2; ++pass) {
      for (const auto& q : basis_) v -= q.dot(v) * q;
    }
    const double residual = v.norm();
    if (!(residual > kDependenceTolerance * norm)) return false;
    if (explained < 1.0 && !(residual * residual > (1.0 - explained) * centred * centred)) {
      return false;
    }
    basis_.push_back(v / residual);
    return true;
  }

 private:
  std::size_t rows_;
  std::vector<Eigen::VectorXd> basis_;
};

}  // namespace

RedundancyFilter::RedundancyFilter(std::shared_ptr<const FeatureSample> sample, bool withOriginal,
                                   int minFeatures, double explained)
    : sample_(std::move(sample)),
      withOriginal_(withOriginal),
      minFeatures_(minFeatures),
      explained_(explained) {}

expr::Genome RedundancyFilter::operator()(const expr::Genome& genome) const {
  Span span(sample_->rows());
  span.add(std::vector<double>(sample_->rows(), 1.0));
  if (withOriginal_) {
    for (std::size_t i = 0; i < sample_->stateDim(); ++i) span.add(sample_->variable(i));
  }
  std::vector<bool> keep(genome.featureCount());
  std::size_t kept = 0;
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    keep[k] = span.add(sample_->column(genome, k), explained_);
    kept += keep[k] ? 1 : 0;
  }
  for (std::size_t k = 0; k < genome.featureCount() && kept < std::size_t(minFeatures_); ++k) {
    if (!keep[k] && !withOriginal_) {
      keep[k] = true;
      ++kept;
    }
  }
  if (kept == genome.featureCount()) return genome;
  expr::Genome out;
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    if (keep[k]) out.addFeature(genome.feature(k));
  }
  const expr::Node placeholder[] = {expr::Node::constant(0.0)};
  while (out.featureCount() < std::size_t(minFeatures_)) out.addFeature(placeholder);
  return out;
}

bool variesOnSample(const expr::Genome& genome, const FeatureSample& sample) {
  const std::vector<double> ones(sample.rows(), 1.0);
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    Span span(sample.rows());
    span.add(ones);
    if (span.add(sample.column(genome, k))) return true;
  }
  return false;
}

bool isPlaceholder(expr::TreeView feature) {
  return feature.size() == 1 && feature[0].op == expr::Op::Const && feature[0].value == 0.0;
}

bool onlyPlaceholders(const expr::Genome& genome) {
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    if (!isPlaceholder(genome.feature(k))) return false;
  }
  return true;
}

expr::Genome withoutPlaceholders(const expr::Genome& genome) {
  expr::Genome out;
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    if (!isPlaceholder(genome.feature(k))) out.addFeature(genome.feature(k));
  }
  return out;
}

expr::Genome normaliseFeatures(const expr::Genome& genome, const FeatureSample& sample) {
  expr::Genome out;
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    const auto values = sample.column(genome, k);
    double mean = 0.0;
    for (const double v : values) mean += v;
    mean /= static_cast<double>(values.size());
    double squares = 0.0;
    for (const double v : values) squares += (v - mean) * (v - mean);
    const double sd = std::sqrt(squares / static_cast<double>(values.size()));
    const double inverse = 1.0 / sd;
    if (!(sd > 0) || !std::isfinite(mean) || !std::isfinite(inverse) || !std::isfinite(sd)) {
      out.addFeature(genome.feature(k));
      continue;
    }
    expr::Tree tree{expr::Node::function(expr::Op::Mul), expr::Node::function(expr::Op::Sub)};
    const auto feature = genome.feature(k);
    tree.insert(tree.end(), feature.begin(), feature.end());
    tree.push_back(expr::Node::constant(mean));
    tree.push_back(expr::Node::constant(inverse));
    expr::recomputeLengths(tree);
    out.addFeature(tree);
  }
  return out;
}

gp::GenomeReducer genomeReducer(const ExperimentConfig& config, const LearningTask& task) {
  if (!config.dropRedundant) return {};
  return RedundancyFilter(task.stateSample(), config.withOriginal, config.limits.minFeatures,
                          config.redundantR2);
}

gp::GenomeFilter genomeAdmissible(const ExperimentConfig& config, const LearningTask& task) {
  if (!config.rejectConstant || config.withOriginal) return {};
  return
      [sample = task.stateSample()](const expr::Genome& g) { return variesOnSample(g, *sample); };
}

}  // namespace gpfd::run
