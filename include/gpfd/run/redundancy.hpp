// run: redundant features out of a feature set before it is evaluated. A linear learner gains
// nothing from a feature that is a linear combination of the others and its bias, but Rprop,
// which steps every weight by its own amount, moves along a repeated direction n times faster:
// short trials reward such repeats and long training does not. A feature is redundant when, on a
// sample of visited states, its values lie in the span of the constant 1, of the original state
// variables when the learner sees them too, and of the features kept before it.
#pragma once

#include <memory>

#include "gpfd/expr/genome.hpp"
#include "gpfd/gp/evolution.hpp"
#include "gpfd/run/state_sample.hpp"

namespace gpfd::run {

// Relative residual below which a column counts as in the span of the others: far above
// rounding (about 1e-15 for an exact combination) and far below any real difference between
// features on visited states (sin(x) against x on |x| <= 0.2 differs by about 7e-3).
inline constexpr double kDependenceTolerance = 1e-8;

class RedundancyFilter {
 public:
  // `minFeatures`: while fewer features remain, dropped ones are kept back, first first; when the
  // learner sees the original variables too, the constant 0 (a placeholder) is kept instead, so
  // that no set hands the learner a second copy of a direction it already has. `explained`
  // (genome.redundant_r2): a feature is also dropped when the span explains at least this share
  // of its variance on the sample, a near copy (sin(sin(u)) beside sin(u): 1 - R^2 about 1e-3),
  // along which Rprop's separate steps let two weights drift apart; 1: exact dependence only.
  RedundancyFilter(std::shared_ptr<const FeatureSample> sample, bool withOriginal, int minFeatures,
                   double explained = 1.0);
  // The genome without its redundant features, the others in their order.
  expr::Genome operator()(const expr::Genome& genome) const;

 private:
  std::shared_ptr<const FeatureSample> sample_;
  bool withOriginal_;
  int minFeatures_;
  double explained_;
};

// Whether some feature of the genome takes more than one value on the sample (genome.
// reject_constant): beyond kDependenceTolerance of the span of the constant 1, non-finite values
// counting as constant.
bool variesOnSample(const expr::Genome& genome, const FeatureSample& sample);

struct ExperimentConfig;
class LearningTask;
// What a run's Evolution applies to every new genome on `task`: genome.drop_redundant's
// RedundancyFilter, and genome.reject_constant's variesOnSample (off beside the original
// variables); empty where the config turns them off.
gp::GenomeReducer genomeReducer(const ExperimentConfig& config, const LearningTask& task);
gp::GenomeFilter genomeAdmissible(const ExperimentConfig& config, const LearningTask& task);

// The placeholder: the constant 0 as a feature. Beside the original variables it stands for "no
// feature": the learner's feature map leaves it out, and a set of placeholders alone is the
// original variables, which validation always scores anyway.
bool isPlaceholder(expr::TreeView feature);
bool onlyPlaceholders(const expr::Genome& genome);
// The genome without its placeholders (possibly empty).
expr::Genome withoutPlaceholders(const expr::Genome& genome);

// Each feature rescaled to zero mean and unit standard deviation on the sample, as an
// expression: f -> (f - mean) * (1 / sd). Features constant on the sample are left alone.
expr::Genome normaliseFeatures(const expr::Genome& genome, const FeatureSample& sample);

}  // namespace gpfd::run
