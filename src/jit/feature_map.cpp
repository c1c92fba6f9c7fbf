#include "gpfd/jit/feature_map.hpp"

#include <algorithm>
#include <stdexcept>

#include "gpfd/expr/eval.hpp"

namespace gpfd::jit {

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

InterpretedFeatureMap::InterpretedFeatureMap(expr::Genome genome, std::size_t inputDim)
    : genome_(std::move(genome)), inputDim_(inputDim) {
  const auto problem =
      expr::checkGenome(genome_, {0, 1 << 20, expr::kMaxParseDepth, expr::kMaxParseSize},
                        static_cast<int>(inputDim_));
  if (!problem.empty()) throw std::invalid_argument("InterpretedFeatureMap: " + problem);
}

void InterpretedFeatureMap::evaluate(const double* state, double* features) const {
  expr::evaluate(genome_, state, features);
}

}  // namespace gpfd::jit
