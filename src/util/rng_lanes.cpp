#include "gpfd/util/rng_lanes.hpp"

#include "gpfd/util/lanes.hpp"
#include "gpfd/util/ziggurat.hpp"

namespace gpfd {
namespace {

using Words = std::uint64_t __attribute__((vector_size(32)));
using Doubles = double __attribute__((vector_size(32)));
// The same at any 8-byte aligned address (one unaligned 32-byte load or store).
using UnalignedWords = std::uint64_t __attribute__((vector_size(32), aligned(8), may_alias));
using UnalignedDoubles = double __attribute__((vector_size(32), aligned(8), may_alias));

// The helpers that take or return 32-byte vectors are AVX2 kernels too: they are only called from
// one, and a 32-byte vector passed to a function without AVX changes its ABI (clang refuses it).
GPFD_AVX2_KERNEL inline Words rotl(Words x, int k) { return (x << k) | (x >> (64 - k)); }

// Exact double of integers below 2^52: their bits under the exponent of 2^52, minus 2^52.
GPFD_AVX2_KERNEL inline Doubles exactDouble(Words x) {
  const Words exponent = {0x4330000000000000u, 0x4330000000000000u, 0x4330000000000000u,
                          0x4330000000000000u};
  return (Doubles)(x | exponent) - 0x1.0p52;
}

// Lanes [4 g, 4 g + 4) for every group g < groups: Rng::operator() (xoshiro256**, the
// multiplications by 5 and 9 as shifts and adds), then standardNormal's fast path; the lanes that
// miss a rectangle finish with ziggurat::slowDraw on their own engine.
GPFD_AVX2_KERNEL void normalGroups(std::uint64_t* words, std::size_t stride, std::size_t groups,
                                   double* out) {
  for (std::size_t g = 0; g < groups; ++g) {
    const auto at = [&](std::size_t w) {
      return reinterpret_cast<UnalignedWords*>(words + w * stride + 4 * g);
    };
    Words s0 = *at(0), s1 = *at(1), s2 = *at(2), s3 = *at(3);
    const Words times5 = (s1 << 2) + s1;
    const Words rotated = rotl(times5, 7);
    const Words word = (rotated << 3) + rotated;
    const Words t = s1 << 17;
    s2 ^= s0;
    s3 ^= s1;
    s1 ^= s2;
    s0 ^= s3;
    s2 ^= t;
    s3 = rotl(s3, 45);
    *at(0) = s0;
    *at(1) = s1;
    *at(2) = s2;
    *at(3) = s3;

    const Words mantissa = word >> 11;  // 53 bits, converted exactly in two parts.
    const Doubles uniform =
        (exactDouble(mantissa >> 32) * 0x1.0p32 + exactDouble(mantissa & 0xffffffffu)) * 0x1.0p-53;
    Doubles width, inner;
    for (int j = 0; j < 4; ++j) {
      const auto layer = static_cast<unsigned>(word[j] & 0xffu);
      width[j] = ziggurat::kLayerX[layer];
      inner[j] = ziggurat::kLayerX[layer + 1];
    }
    const Doubles z = uniform * width;
    const Words sign = (word & 0x100u) << 55;  // Bit 8 moved to the sign bit.
    Doubles value = (Doubles)((Words)z ^ sign);
    const auto inside = z < inner;
    if ((inside[0] & inside[1] & inside[2] & inside[3]) == 0) {
      for (int j = 0; j < 4; ++j) {
        if (inside[j] != 0) continue;
        const std::size_t lane = 4 * g + static_cast<std::size_t>(j);
        Rng::State state{};
        for (int w = 0; w < 4; ++w) state.words[w] = words[w * stride + lane];
        Rng rng;
        rng.setState(state);
        value[j] = ziggurat::slowDraw(rng, word[j]);
        state = rng.state();
        for (int w = 0; w < 4; ++w) words[w * stride + lane] = state.words[w];
      }
    }
    *reinterpret_cast<UnalignedDoubles*>(out + 4 * g) = value;
  }
}

}  // namespace

RngLanes::RngLanes(std::size_t lanes)
    : lanes_(lanes), stride_((lanes + 3) / 4 * 4), words_(4 * stride_, 0) {}

void RngLanes::set(std::size_t lane, const Rng& rng) {
  const Rng::State state = rng.state();
  for (int w = 0; w < 4; ++w) words_[static_cast<std::size_t>(w) * stride_ + lane] = state.words[w];
}

Rng RngLanes::get(std::size_t lane) const {
  Rng::State state{};
  for (int w = 0; w < 4; ++w) state.words[w] = words_[static_cast<std::size_t>(w) * stride_ + lane];
  Rng rng;
  rng.setState(state);
  return rng;
}

void RngLanes::move(std::size_t from, std::size_t to) {
  for (std::size_t w = 0; w < 4; ++w) words_[w * stride_ + to] = words_[w * stride_ + from];
}

void RngLanes::standardNormal(std::size_t n, double* out, bool avx2) {
  std::size_t l = 0;
  if (avx2) {
    normalGroups(words_.data(), stride_, n / 4, out);
    l = n / 4 * 4;
  }
  for (; l < n; ++l) {
    Rng rng = get(l);
    out[l] = gpfd::standardNormal(rng);
    set(l, rng);
  }
}

}  // namespace gpfd
