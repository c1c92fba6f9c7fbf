// jit: the project's fastest interpreter. A genome is lowered once (constant folding,
// simplification, shared sub-expressions; see program.hpp) and each call runs the straight-line
// program over a scratch array: no recursion, no tree walking, each distinct value computed once.
// It is also the fallback of CompiledFeatureMap when native code cannot be used.
#pragma once

#include "gpfd/features/feature_map.hpp"
#include "gpfd/jit/program.hpp"

namespace gpfd::jit {

class FastInterpretedFeatureMap final : public features::FeatureMap {
 public:
  // Throws LowerError when the genome is malformed or reads a variable >= inputDim.
  FastInterpretedFeatureMap(const expr::Genome& genome, std::size_t inputDim);
  explicit FastInterpretedFeatureMap(Program program);

  std::size_t inputDim() const override { return program_.inputDim; }
  std::size_t outputDim() const override { return program_.outputs.size(); }
  void evaluate(const double* state, double* features) const override;
  void evaluateBatch(const double* states, std::size_t n, double* out) const override;
  const Program& program() const { return program_; }

 private:
  Program program_;
};

}  // namespace gpfd::jit
