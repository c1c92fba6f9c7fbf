#include "gpfd/features/feature_map.hpp"

#include <algorithm>
#include <stdexcept>

namespace gpfd::features {

void FeatureMap::evaluateBatch(const double* states, std::size_t n, double* out) const {
  const std::size_t in = inputDim(), k = outputDim();
  for (std::size_t i = 0; i < n; ++i) evaluate(states + i * in, out + i * k);
}

void RawFeatureMap::evaluate(const double* state, double* features) const {
  std::copy(state, state + dim_, features);
}

ConcatFeatureMap::ConcatFeatureMap(std::vector<std::shared_ptr<const FeatureMap>> parts)
    : parts_(std::move(parts)) {
  if (parts_.empty()) throw std::invalid_argument("ConcatFeatureMap needs at least one part");
  inputDim_ = parts_.front()->inputDim();
  for (const auto& part : parts_) {
    if (part->inputDim() != inputDim_) {
      throw std::invalid_argument("ConcatFeatureMap parts disagree on the state dimension");
    }
    outputDim_ += part->outputDim();
  }
}

void ConcatFeatureMap::evaluate(const double* state, double* features) const {
  for (const auto& part : parts_) {
    part->evaluate(state, features);
    features += part->outputDim();
  }
}

}  // namespace gpfd::features
