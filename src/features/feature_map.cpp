#include "gpfd/features/feature_map.hpp"

#include <algorithm>
#include <stdexcept>

namespace gpfd::features {

void FeatureMap::evaluateBatch(const double* states, std::size_t n, double* out) const {
  const std::size_t in = inputDim(), k = outputDim();
  for (std::size_t i = 0; i < n; ++i) evaluate(states + i * in, out + i * k);
}

void FeatureMap::evaluateLaneBlocks(const double* blocks, std::size_t groups, double* out) const {
  const std::size_t in = inputDim(), k = outputDim();
  thread_local std::vector<double> state, features;  // No allocation once grown.
  state.resize(in);
  features.resize(k);
  for (std::size_t g = 0; g < groups; ++g, blocks += 4 * in, out += 4 * k) {
    for (std::size_t lane = 0; lane < 4; ++lane) {
      for (std::size_t i = 0; i < in; ++i) state[i] = blocks[i * 4 + lane];
      evaluate(state.data(), features.data());
      for (std::size_t j = 0; j < k; ++j) out[j * 4 + lane] = features[j];
    }
  }
}

void RawFeatureMap::evaluate(const double* state, double* features) const {
  std::copy(state, state + dim_, features);
}

void RawFeatureMap::evaluateLaneBlocks(const double* blocks, std::size_t groups,
                                       double* out) const {
  std::copy(blocks, blocks + groups * 4 * dim_, out);  // The features' blocks are the states'.
}

void ZeroFeatureMap::evaluate(const double* /*state*/, double* features) const {
  features[0] = 0.0;
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
