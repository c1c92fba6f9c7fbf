// util: NumPy's default random stream, bit for bit, for environments that must draw what
// Gymnasium's draw (the twins of classic control, env/gymnasium_twin.hpp). Gymnasium seeds an
// environment with np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed)))
// (gymnasium/utils/seeding.py, Gymnasium 1.1-1.4). The algorithms, from NumPy 2.x's
// numpy/random/bit_generator.pyx (SeedSequence), numpy/random/src/pcg64/pcg64.h (PCG64) and
// numpy/random/src/distributions/distributions.c (uniform), and O'Neill 2014, "PCG: a family of
// simple fast space-efficient statistically good algorithms for random number generation".
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace gpfd::numpy {

__extension__ typedef unsigned __int128 Uint128;

// np.random.SeedSequence(entropy) without spawn keys, as PCG64 consumes it: the entropy is an
// integer >= 0 given as 32-bit words, least significant first (NumPy's own split of a Python
// int), hashed into a pool of 4 words.
class SeedSequence {
 public:
  explicit SeedSequence(std::span<const std::uint32_t> entropyWords);
  // generate_state(n, np.uint32).
  std::vector<std::uint32_t> generateState32(std::size_t words) const;
  // generate_state(n, np.uint64): pairs of 32-bit words, the first the low half.
  std::vector<std::uint64_t> generateState64(std::size_t words) const;

  // The 32-bit words of a non-negative integer, least significant first ([0] for 0).
  static std::vector<std::uint32_t> wordsOf(std::uint64_t value);

 private:
  std::array<std::uint32_t, 4> pool_{};
};

// np.random.PCG64: a 128-bit LCG with the XSL-RR output function, seeded from a SeedSequence.
class Pcg64 {
 public:
  explicit Pcg64(const SeedSequence& seeds);
  std::uint64_t next64();
  // Generator.random(): 53 random bits in [0, 1).
  double nextDouble() { return static_cast<double>(next64() >> 11) * (1.0 / 9007199254740992.0); }
  // Generator.uniform(low, high) for one value: low + (high - low) * random().
  double uniform(double low, double high) { return low + (high - low) * nextDouble(); }

  // The whole state (snapshots): state high, state low, increment high, increment low.
  std::array<std::uint64_t, 4> words() const;
  void setWords(const std::array<std::uint64_t, 4>& words);

 private:
  Pcg64() = default;
  void step() { state_ = state_ * kMultiplier + increment_; }

  // PCG's default 128-bit multiplier (pcg64.h: PCG_DEFAULT_MULTIPLIER_128).
  static constexpr Uint128 kMultiplier =
      (static_cast<Uint128>(0x2360ed051fc65da4ULL) << 64) | 0x4385df649fccf645ULL;
  Uint128 state_ = 0;
  Uint128 increment_ = 1;
};

}  // namespace gpfd::numpy
