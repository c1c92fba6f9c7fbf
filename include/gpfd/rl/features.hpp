// rl: the features a linear learner sees: a feature map's outputs, optionally normalised online
// by a running mean and standard deviation, optionally followed by a constant bias feature.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/util/params.hpp"

namespace gpfd::rl {

struct FeatureOptions {
  // Append a constant 1 after the map's features.
  bool bias = true;
  // Online normalisation: features become (phi - mean) / std with the running mean and standard
  // deviation of every feature seen so far. The statistics are frozen while a batch is played
  // and refreshed at each update; the weights are then re-expressed so that the learned function
  // does not jump (exactly when a bias is present; without one only the scale is normalised).
  // Off by default, as in the paper.
  bool normalise = false;
};

// Declares `bias` and `normalise` in a learner's parameter table; `options` returns the config's
// FeatureOptions (a generic lambda, as the fields of a ParamTable).
template <typename Config, typename Options>
void declareFeatureParams(ParamTable<Config>& table, Options options) {
  table.flag(
      "bias", [options](auto& c) -> auto& { return options(c).bias; }, "append a constant feature");
  table.flag(
      "normalise", [options](auto& c) -> auto& { return options(c).normalise; },
      "running mean/std feature normalisation");
}

// Running mean and sum of squared deviations of raw feature rows (Welford), mergeable.
struct FeatureMoments {
  std::int64_t count = 0;
  std::vector<double> mean, m2;

  explicit FeatureMoments(std::size_t dim = 0) : mean(dim, 0.0), m2(dim, 0.0) {}
  void clear();
  // Adds one row, value j at row[j * stride].
  void add(const double* row, std::size_t stride = 1);
  // Adds the rows summarised by `other` (Chan, Golub & LeVeque 1979, pairwise update).
  void merge(const FeatureMoments& other);
};

// Not thread-safe (it keeps statistics); one per learning run.
class FeaturePipeline {
 public:
  FeaturePipeline(const features::FeatureMap& map, const FeatureOptions& options);

  std::size_t stateDim() const { return map_->inputDim(); }
  std::size_t rawDim() const { return raw_; }
  std::size_t dim() const { return raw_ + (options_.bias ? 1 : 0); }
  const FeatureOptions& options() const { return options_; }

  // Features of one state into out[0, dim()). Returns false when a feature is not finite.
  bool evaluate(const double* state, double* out);
  // n states (n * stateDim() values) to n rows of dim() features. Returns false when a feature
  // is not finite.
  bool evaluateBatch(const double* states, std::size_t n, double* out);

  // The learner's features from a row of raw features (rawDim() values, dim() of room) in place,
  // without touching the statistics: false when a raw value is not finite; else normalised with
  // the current snapshot, the bias appended. Policy gradient gathers each episode's moments
  // itself and merges them in episode order, so that episodes may be played side by side.
  bool transform(double* row) const;
  // Adds an episode's moments to the statistics.
  void merge(const FeatureMoments& moments);
  const std::vector<double>& shift() const { return shift_; }
  const std::vector<double>& scale() const { return scale_; }

  // Refreshes the normalisation from the statistics gathered so far and re-expresses
  // `weights` (rows x dim(), row-major, followed by anything else, which is left alone) so that
  // every output keeps its value. No-op when not normalising.
  void refresh(double* weights, std::size_t rows);

  // Exports the normalisation (shift/scale) into `out`; imports it from `in` (for evaluation of
  // trained weights). Sizes are checked by the caller.
  void exportTo(LinearWeights& out) const;
  void importFrom(const LinearWeights& in);

 private:
  bool finish(double* row);  // Record statistics, normalise, append the bias; false if not finite.
  void normaliseAndBias(double* row) const;  // transform of a row known to be finite.

  const features::FeatureMap* map_;
  FeatureOptions options_;
  std::size_t raw_;
  std::vector<double> shift_, scale_;  // Current snapshot.
  FeatureMoments moments_;             // Running statistics.
};

}  // namespace gpfd::rl
