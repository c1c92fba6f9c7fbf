#include "gpfd/jit/compiled_feature_map.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace gpfd::jit {
namespace {

void warnOnce(const std::string& reason) {
  static std::atomic<bool> warned{false};
  if (!warned.exchange(true)) {
    std::fprintf(stderr, "gpfd: JIT unavailable (%s); features run on the interpreter\n",
                 reason.c_str());
  }
}

bool disabledByEnvironment() {
  const char* value = std::getenv("GPFD_NO_JIT");
  return value != nullptr && std::strcmp(value, "") != 0 && std::strcmp(value, "0") != 0;
}

}  // namespace

CompiledFeatureMap::CompiledFeatureMap(const expr::Genome& genome, std::size_t inputDim)
    : CompiledFeatureMap(genome, inputDim, CompileOptions{}) {}

CompiledFeatureMap::CompiledFeatureMap(const expr::Genome& genome, std::size_t inputDim,
                                       CompileOptions options)
    : interpreter_(genome, inputDim) {
  if (!options.native) {
    reason_ = "native code not requested";
    return;
  }
  if (!jitAvailable()) {
    reason_ = "this build has no JIT (GPFD_WITH_JIT=OFF or not x86-64)";
  } else if (disabledByEnvironment()) {
    reason_ = "disabled by GPFD_NO_JIT";
  } else {
    try {
      scalarCode_ = compileScalar(interpreter_.program());
      scalar_ = reinterpret_cast<ScalarFunction>(scalarCode_.entry());
    } catch (const CompileError& e) {
      reason_ = e.what();
    }
  }
  if (!scalar_) {
    warnOnce(reason_);
    return;
  }
  if (options.batch && hostHasAvx2()) {
    try {
      batchCode_ = compileBatch(interpreter_.program());
      batch_ = reinterpret_cast<BatchKernel>(batchCode_.entry());
      blocksCode_ = compileLaneBlocks(interpreter_.program());
      blocks_ = reinterpret_cast<BatchKernel>(blocksCode_.entry());
    } catch (const CompileError&) {
      // The batch then runs the scalar function per state; nothing is lost but speed.
    }
  }
}

void CompiledFeatureMap::evaluate(const double* state, double* features) const {
  if (scalar_) {
    scalar_(state, features);
  } else {
    interpreter_.evaluate(state, features);
  }
}

void CompiledFeatureMap::evaluateBatch(const double* states, std::size_t n, double* out) const {
  if (!scalar_) {
    interpreter_.evaluateBatch(states, n, out);
    return;
  }
  const std::size_t in = inputDim(), k = outputDim();
  std::size_t done = 0;
  if (batch_) {
    batch_(states, n / 4, out);
    done = n / 4 * 4;
  }
  for (std::size_t i = done; i < n; ++i) scalar_(states + i * in, out + i * k);
}

void CompiledFeatureMap::evaluateLaneBlocks(const double* blocks, std::size_t groups,
                                            double* out) const {
  if (blocks_) {
    blocks_(blocks, groups, out);
  } else {
    FeatureMap::evaluateLaneBlocks(blocks, groups, out);
  }
}

}  // namespace gpfd::jit
