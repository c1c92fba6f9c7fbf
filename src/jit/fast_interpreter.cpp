#include "gpfd/jit/fast_interpreter.hpp"

#include <vector>

namespace gpfd::jit {
namespace {
// Programs up to this many values run with their scratch array on the stack.
constexpr std::size_t kStackValues = 512;
}  // namespace

FastInterpretedFeatureMap::FastInterpretedFeatureMap(const expr::Genome& genome,
                                                     std::size_t inputDim)
    : program_(lower(genome, inputDim)) {}

FastInterpretedFeatureMap::FastInterpretedFeatureMap(Program program)
    : program_(std::move(program)) {}

void FastInterpretedFeatureMap::evaluate(const double* state, double* features) const {
  if (program_.code.size() <= kStackValues) {
    double scratch[kStackValues];
    run(program_, state, features, scratch);
  } else {
    std::vector<double> scratch(program_.code.size());
    run(program_, state, features, scratch.data());
  }
}

void FastInterpretedFeatureMap::evaluateBatch(const double* states, std::size_t n,
                                              double* out) const {
  std::vector<double> heap(program_.code.size() > kStackValues ? program_.code.size() : 0);
  double local[kStackValues];
  double* scratch = heap.empty() ? local : heap.data();
  const std::size_t in = inputDim(), k = outputDim();
  for (std::size_t i = 0; i < n; ++i) run(program_, states + i * in, out + i * k, scratch);
}

}  // namespace gpfd::jit
