// jit: the asmjit compiler from a lowered Program to native x86-64 code. Code is emitted directly
// with the Assembler in one pass (a linear-scan register allocator over the straight-line program,
// xmm0..xmm13 for values, xmm14/xmm15 as scratch), so compiling costs microseconds.
//
// Entry points (System V x86-64 ABI):
// - ScalarFunction: features[k] = output k on one state, scalar SSE2 code.
// - BatchKernel: `groups` groups of 4 consecutive states (states: groups*4*inputDim doubles, out:
//   groups*4*outputDim doubles), AVX2 code with one state per ymm lane.
// - Lane-block kernel (same signature), the lockstep learners' layout: the states of a group in a
//   block of inputDim rows of 4 lanes, variable i of lane l at states[(g * inputDim + i) * 4 + l];
//   features likewise (out[(g * outputDim + k) * 4 + l]). A variable is one load and a feature one
//   store, where state rows need four loads and a shuffle per variable.
// All three read only state[0, inputDim) per state and write only features[0, outputDim); results
// are bit-identical to expr::evaluate (the protected semantics of expr/ops.hpp; sin, cos, exp, log
// and tanh call the same libm functions as the interpreter). State and feature buffers must not
// overlap.
#pragma once

#include <cstddef>
#include <stdexcept>

#include "gpfd/jit/program.hpp"

namespace gpfd::jit {

using ScalarFunction = void (*)(const double* state, double* features);
using BatchKernel = void (*)(const double* states, std::size_t groups, double* out);

// Spill frames stay within one 4 KiB page below the caller's stack pointer, so that generated code
// can never step over a guard page; a program needing more simultaneously live spilled values
// than fit (kMaxScalarSpills / kMaxBatchSpills) is refused with CompileError.
inline constexpr std::size_t kFrameBytes = 4096 - 64;
inline constexpr std::size_t kMaxScalarSpills = kFrameBytes / 8;
inline constexpr std::size_t kMaxBatchSpills = (kFrameBytes - 32) / 32;

// The JIT cannot compile this program here: no JIT in this build, no AVX2 (batch kernels), an
// asmjit error, or the program needs more spill space than the frame limit.
class CompileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Owns one function in the process-wide code runtime; the code is released when this dies.
class NativeCode {
 public:
  NativeCode() = default;
  // `base`: the allocation in the runtime; `entry`: the function inside it.
  NativeCode(void* base, void* entry, std::size_t bytes)
      : base_(base), entry_(entry), bytes_(bytes) {}
  NativeCode(NativeCode&& other) noexcept { swap(other); }
  NativeCode& operator=(NativeCode&& other) noexcept {
    NativeCode tmp(std::move(other));
    swap(tmp);
    return *this;
  }
  NativeCode(const NativeCode&) = delete;
  NativeCode& operator=(const NativeCode&) = delete;
  ~NativeCode();

  void* entry() const { return entry_; }
  std::size_t bytes() const { return bytes_; }  // Code plus constant pool.
  explicit operator bool() const { return entry_ != nullptr; }

 private:
  void swap(NativeCode& other) noexcept {
    std::swap(base_, other.base_);
    std::swap(entry_, other.entry_);
    std::swap(bytes_, other.bytes_);
  }
  void* base_ = nullptr;
  void* entry_ = nullptr;
  std::size_t bytes_ = 0;
};

// Whether this build has the JIT (GPFD_HAVE_JIT on x86-64).
bool jitAvailable();
// Whether the host CPU (and OS) run AVX2 code, by asmjit's CpuInfo.
bool hostHasAvx2();
// Whether it runs AVX (VEX-encoded) code; the scalar function then uses some AVX instructions.
bool hostHasAvx();
// Whether executable code is mapped without a writable view at the same address (asmjit dual
// mapping); false when the runtime had to fall back to read-write-execute pages.
bool jitUsesDualMapping();

// Compiles `program` to a ScalarFunction. Throws CompileError.
NativeCode compileScalar(const Program& program);
// Compiles `program` to an AVX2 BatchKernel. Throws CompileError (also without AVX2).
NativeCode compileBatch(const Program& program);
// Compiles `program` to an AVX2 BatchKernel on lane blocks. Throws CompileError.
NativeCode compileLaneBlocks(const Program& program);

}  // namespace gpfd::jit
