// env: the loop shared by the batched environments: it loads the lanes of a structure-of-arrays
// batch (env/batch.hpp) into std::array<T, S> states, runs a kernel written over the number type
// T, and stores the results back. T is Lanes8 (eight lanes at a time, compiled as AVX-512), Lanes4
// (four lanes at a time, compiled as AVX2; a last partial group is padded with copies of its last
// lane) or double (one lane at a time).
//
// A kernel: template <class T> lanes::MaskOf<T> operator()(std::array<T, S>& state,
//   const std::array<T, A>& action, T& reward) const, returning `terminated`.
#pragma once

#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>

#include "gpfd/env/batch.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/lanes.hpp"

namespace gpfd::env::batch {

// Throws InputError unless every lane's discrete action (one component) is an integer in
// [0, choices).
inline void checkChoices(const BatchBuffers& io, int choices, const std::string& env) {
  for (std::size_t l = 0; l < io.lanes; ++l) {
    const double a = io.action[l];
    if (!(a >= 0.0 && a < choices && a == static_cast<int>(a))) {
      throw InputError(fmt::format("{} discrete action must be 0..{}, got {} in lane {}", env,
                                   choices - 1, a, l),
                       fmt::format("{} action", env));
    }
  }
}

// One group of lanes at `lane` of buffers whose rows are `stride` apart.
template <std::size_t S, std::size_t A, class T, class Kernel>
void stepGroup(const Kernel& kernel, double* state, const double* action, std::size_t stride,
               double* reward, std::uint8_t* terminated) {
  std::array<T, S> s;
  std::array<T, A> a;
  if constexpr (std::is_same_v<T, double>) {
    for (std::size_t i = 0; i < S; ++i) s[i] = state[i * stride];
    for (std::size_t c = 0; c < A; ++c) a[c] = action[c * stride];
    *terminated = kernel(s, a, *reward) ? 1 : 0;
    for (std::size_t i = 0; i < S; ++i) state[i * stride] = s[i];
  } else {
    for (std::size_t i = 0; i < S; ++i) s[i] = lanes::loadAs<T>(state + i * stride);
    for (std::size_t c = 0; c < A; ++c) a[c] = lanes::loadAs<T>(action + c * stride);
    T r;
    const lanes::MaskOf<T> done = kernel(s, a, r);
    for (std::size_t i = 0; i < S; ++i) lanes::store(state + i * stride, s[i]);
    lanes::store(reward, r);
    const unsigned bits = lanes::bitsOf(done);
    for (std::size_t j = 0; j < lanes::kWidth<T>; ++j) terminated[j] = (bits >> j) & 1u;
  }
}

template <std::size_t S, std::size_t A, class Kernel>
void stepScalar(const Kernel& kernel, const BatchBuffers& io) {
  for (std::size_t l = 0; l < io.lanes; ++l) {
    stepGroup<S, A, double>(kernel, io.state + l, io.action + l, io.stride, io.reward + l,
                            io.terminated + l);
  }
}

// Groups of four lanes from lane `l` on; a last partial group is stepped in the scratch tail or
// padded with copies of its last lane.
template <std::size_t S, std::size_t A, class Kernel>
void stepFours(const Kernel& kernel, const BatchBuffers& io, std::size_t l) {
  for (; l + 4 <= io.lanes; l += 4) {
    stepGroup<S, A, lanes::Lanes4>(kernel, io.state + l, io.action + l, io.stride, io.reward + l,
                                   io.terminated + l);
  }
  if (l == io.lanes) return;
  if (io.scratchTail) {
    stepGroup<S, A, lanes::Lanes4>(kernel, io.state + l, io.action + l, io.stride, io.reward + l,
                                   io.terminated + l);
    return;
  }
  // The last 1-3 lanes, padded to a group with copies of the last one.
  const std::size_t rest = io.lanes - l;
  double state[S * 4], action[A > 0 ? A * 4 : 1], reward[4];
  std::uint8_t terminated[4];
  for (std::size_t j = 0; j < 4; ++j) {
    const std::size_t from = l + (j < rest ? j : rest - 1);
    for (std::size_t i = 0; i < S; ++i) state[i * 4 + j] = io.state[i * io.stride + from];
    for (std::size_t c = 0; c < A; ++c) action[c * 4 + j] = io.action[c * io.stride + from];
  }
  stepGroup<S, A, lanes::Lanes4>(kernel, state, action, 4, reward, terminated);
  for (std::size_t j = 0; j < rest; ++j) {
    for (std::size_t i = 0; i < S; ++i) io.state[i * io.stride + l + j] = state[i * 4 + j];
    io.reward[l + j] = reward[j];
    io.terminated[l + j] = terminated[j];
  }
}

template <std::size_t S, std::size_t A, class Kernel>
GPFD_AVX2_KERNEL void stepAvx2(const Kernel& kernel, const BatchBuffers& io) {
  stepFours<S, A>(kernel, io, 0);
}

// Groups of eight lanes (Lanes8: one chain of 512-bit operations), then of four.
template <std::size_t S, std::size_t A, class Kernel>
GPFD_AVX512_KERNEL void stepAvx512(const Kernel& kernel, const BatchBuffers& io) {
  std::size_t l = 0;
  for (; l + 8 <= io.lanes; l += 8) {
    stepGroup<S, A, lanes::Lanes8>(kernel, io.state + l, io.action + l, io.stride, io.reward + l,
                                   io.terminated + l);
  }
  stepFours<S, A>(kernel, io, l);
}

// Steps every lane with `kernel`, then counts the step and applies the time limit `maxSteps`
// (0: none), as the scalar environments do. `isa` is resolved; Avx512 steps eight lanes at a time
// only for a kernel that accepts Lanes8 (Wide), four at a time otherwise.
template <std::size_t S, std::size_t A, bool Wide = false, class Kernel>
void stepAll(const Kernel& kernel, const BatchBuffers& io, BatchIsa isa, int maxSteps) {
  if (Wide && isa == BatchIsa::Avx512) {
    if constexpr (Wide) stepAvx512<S, A>(kernel, io);
  } else if (isa != BatchIsa::Scalar) {
    stepAvx2<S, A>(kernel, io);
  } else {
    stepScalar<S, A>(kernel, io);
  }
  for (std::size_t l = 0; l < io.lanes; ++l) {
    ++io.elapsed[l];
    io.truncated[l] = maxSteps > 0 && io.elapsed[l] >= maxSteps ? 1 : 0;
  }
}

}  // namespace gpfd::env::batch
