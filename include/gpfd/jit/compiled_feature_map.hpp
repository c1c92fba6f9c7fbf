// jit: a genome's features as native code: the whole genome is one function
// void(const double* state, double* features), plus two AVX2 batch kernels (state rows, lane
// blocks) where the CPU has AVX2.
// It owns its code (released when the map dies) and behaves exactly like the interpreters
// (bit-identical features), so a learner cannot tell which one it got. When native code cannot
// be used (a build without the JIT, a non-x86-64 host, GPFD_NO_JIT=1 in the environment, or an
// asmjit error) it falls back to FastInterpretedFeatureMap and says so once per process on stderr.
#pragma once

#include <optional>
#include <string>

#include "gpfd/features/feature_map.hpp"
#include "gpfd/jit/fast_interpreter.hpp"
#include "gpfd/jit/x86_compiler.hpp"

namespace gpfd::jit {

struct CompileOptions {
  bool native = true;  // false: use the interpreter (no message).
  bool batch = true;   // Also compile the AVX2 batch kernels when the CPU has AVX2.
};

class CompiledFeatureMap final : public features::FeatureMap {
 public:
  // Throws LowerError (a std::invalid_argument) before compiling anything when the genome is
  // malformed, reads a variable >= inputDim, or exceeds the limits of program.hpp.
  CompiledFeatureMap(const expr::Genome& genome, std::size_t inputDim);
  CompiledFeatureMap(const expr::Genome& genome, std::size_t inputDim, CompileOptions options);
  // Not copyable or movable: the entry points point into the code this object owns.
  CompiledFeatureMap(const CompiledFeatureMap&) = delete;
  CompiledFeatureMap& operator=(const CompiledFeatureMap&) = delete;

  std::size_t inputDim() const override { return interpreter_.inputDim(); }
  std::size_t outputDim() const override { return interpreter_.outputDim(); }
  void evaluate(const double* state, double* features) const override;
  void evaluateBatch(const double* states, std::size_t n, double* out) const override;
  void evaluateLaneBlocks(const double* blocks, std::size_t groups, double* out) const override;

  // Whether evaluate() runs native code; otherwise fallbackReason() says why not.
  bool isNative() const { return scalar_ != nullptr; }
  // Whether evaluateBatch() and evaluateLaneBlocks() run AVX2 kernels (4 states per iteration).
  bool hasNativeBatch() const { return batch_ != nullptr; }
  bool hasNativeLaneBlocks() const { return blocks_ != nullptr; }
  const std::string& fallbackReason() const { return reason_; }
  const Program& program() const { return interpreter_.program(); }

 private:
  FastInterpretedFeatureMap interpreter_;
  NativeCode scalarCode_, batchCode_, blocksCode_;
  ScalarFunction scalar_ = nullptr;
  BatchKernel batch_ = nullptr, blocks_ = nullptr;  // State rows; lane blocks.
  std::string reason_;
};

}  // namespace gpfd::jit
