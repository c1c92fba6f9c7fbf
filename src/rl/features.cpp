#include "gpfd/rl/features.hpp"

#include <algorithm>
#include <cmath>

#include "gpfd/util/finite.hpp"

namespace gpfd::rl {

FeaturePipeline::FeaturePipeline(const features::FeatureMap& map, const FeatureOptions& options)
    : map_(&map),
      options_(options),
      raw_(map.outputDim()),
      shift_(raw_, 0.0),
      scale_(raw_, 1.0),
      moments_(raw_) {}

void FeatureMoments::clear() {
  count = 0;
  std::fill(mean.begin(), mean.end(), 0.0);
  std::fill(m2.begin(), m2.end(), 0.0);
}

void FeatureMoments::add(const double* row, std::size_t stride) {
  ++count;
  const double n = static_cast<double>(count);
  for (std::size_t j = 0; j < mean.size(); ++j) {
    // Welford's update of the running mean and sum of squared deviations.
    const double x = row[j * stride];
    const double delta = x - mean[j];
    mean[j] += delta / n;
    m2[j] += delta * (x - mean[j]);
  }
}

void FeatureMoments::merge(const FeatureMoments& other) {
  if (other.count == 0) return;
  if (count == 0) {
    *this = other;
    return;
  }
  const double na = static_cast<double>(count), nb = static_cast<double>(other.count);
  const double n = na + nb;
  for (std::size_t j = 0; j < mean.size(); ++j) {
    const double delta = other.mean[j] - mean[j];
    mean[j] += delta * (nb / n);
    m2[j] += other.m2[j] + delta * delta * (na * nb / n);
  }
  count += other.count;
}

bool FeaturePipeline::transform(double* row) const {
  if (!allFinite({row, raw_})) return false;
  normaliseAndBias(row);
  return true;
}

void FeaturePipeline::normaliseAndBias(double* row) const {
  if (options_.normalise) {
    for (std::size_t j = 0; j < raw_; ++j) row[j] = (row[j] - shift_[j]) / scale_[j];
  }
  if (options_.bias) row[raw_] = 1.0;
}

void FeaturePipeline::merge(const FeatureMoments& moments) { moments_.merge(moments); }

bool FeaturePipeline::finish(double* row) {
  if (!allFinite({row, raw_})) return false;
  if (options_.normalise) moments_.add(row);
  normaliseAndBias(row);
  return true;
}

bool FeaturePipeline::evaluate(const double* state, double* out) {
  map_->evaluate(state, out);
  return finish(out);
}

bool FeaturePipeline::evaluateBatch(const double* states, std::size_t n, double* out) {
  const std::size_t width = dim();
  if (!options_.bias) {
    map_->evaluateBatch(states, n, out);
  } else {
    // The map writes rows of raw_ values: one batch call, then each row moved to its place (from
    // the last, so that no row is overwritten before it moves), leaving room for the bias.
    map_->evaluateBatch(states, n, out);
    for (std::size_t i = n; i-- > 1;) {
      std::copy_backward(out + i * raw_, out + (i + 1) * raw_, out + i * width + raw_);
    }
  }
  bool finite = true;
  for (std::size_t i = 0; i < n; ++i) finite = finish(out + i * width) && finite;
  return finite;
}

void FeaturePipeline::refresh(double* weights, std::size_t rows) {
  if (!options_.normalise || moments_.count < 2) return;
  const std::size_t width = dim();
  std::vector<double> newShift(raw_), newScale(raw_);
  for (std::size_t j = 0; j < raw_; ++j) {
    const double sd = std::sqrt(moments_.m2[j] / static_cast<double>(moments_.count - 1));
    newScale[j] = (std::isfinite(sd) && sd > 1e-12) ? sd : 1.0;
    newShift[j] = options_.bias ? moments_.mean[j] : 0.0;
  }
  // Output w.(phi - s)/c + b must stay the same under (s', c'):
  // w'_j = w_j c'_j / c_j, b' = b + sum_j w_j (s'_j - s_j) / c_j.
  for (std::size_t r = 0; r < rows; ++r) {
    double* w = weights + r * width;
    double biasShift = 0.0;
    for (std::size_t j = 0; j < raw_; ++j) {
      biasShift += w[j] * (newShift[j] - shift_[j]) / scale_[j];
      w[j] *= newScale[j] / scale_[j];
    }
    if (options_.bias) w[raw_] += biasShift;
  }
  shift_ = std::move(newShift);
  scale_ = std::move(newScale);
}

void FeaturePipeline::exportTo(LinearWeights& out) const {
  out.bias = options_.bias;
  if (options_.normalise) {
    out.shift = shift_;
    out.scale = scale_;
  } else {
    out.shift.clear();
    out.scale.clear();
  }
}

void FeaturePipeline::importFrom(const LinearWeights& in) {
  if (in.shift.size() == raw_ && in.scale.size() == raw_) {
    shift_ = in.shift;
    scale_ = in.scale;
  }
}

}  // namespace gpfd::rl
