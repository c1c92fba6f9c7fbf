// util: the one random engine of gpfd, and the seeding scheme that makes results independent of
// the number of threads or MPI ranks.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

namespace gpfd {

__extension__ typedef unsigned __int128 Uint128;  // GCC/Clang extension, for Rng::below.

// SplitMix64 step (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators"):
// a bijective 64-bit mixer, used to expand seeds and to hash seed tuples.
constexpr std::uint64_t splitmix64(std::uint64_t& state) {
  state += 0x9e3779b97f4a7c15ULL;
  std::uint64_t z = state;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Derives the seed of a sub-stream from a parent seed and a tuple of indices, e.g.
// deriveSeed(runSeed, {generation, individual, trial}). Order matters; never uses thread ids.
template <typename... Index>
constexpr std::uint64_t deriveSeed(std::uint64_t seed, Index... index) {
  std::uint64_t state = seed;
  std::uint64_t out = splitmix64(state);
  ((state = out ^ (static_cast<std::uint64_t>(index) * 0xd1b54a32d192ed03ULL),
    out = splitmix64(state)),
   ...);
  return out;
}

// xoshiro256** 1.0 (Blackman & Vigna 2018), seeded through SplitMix64 as its authors advise.
// Satisfies UniformRandomBitGenerator, but gpfd code uses the member draws below, whose results
// are identical on every platform (unlike the std:: distributions).
class Rng {
 public:
  using result_type = std::uint64_t;

  explicit Rng(std::uint64_t seed = 0) { reseed(seed); }

  void reseed(std::uint64_t seed) {
    std::uint64_t s = seed;
    for (auto& word : state_) word = splitmix64(s);
  }

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

  result_type operator()() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>((*this)() >> 11) * 0x1.0p-53; }

  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  // Uniform integer in [0, n), n > 0, without modulo bias (Lemire 2019).
  std::uint64_t below(std::uint64_t n) {
    Uint128 m = static_cast<Uint128>((*this)()) * n;
    auto low = static_cast<std::uint64_t>(m);
    if (low < n) {
      const std::uint64_t threshold = (0 - n) % n;
      while (low < threshold) {
        m = static_cast<Uint128>((*this)()) * n;
        low = static_cast<std::uint64_t>(m);
      }
    }
    return static_cast<std::uint64_t>(m >> 64);
  }

  // Uniform integer in [lo, hi], lo <= hi.
  int between(int lo, int hi) {
    return lo + static_cast<int>(below(static_cast<std::uint64_t>(hi - lo) + 1));
  }

  bool bernoulli(double p) { return uniform() < p; }

  // Standard normal by the Marsaglia polar method; the spare value is kept for the next call.
  double normal() {
    if (hasSpare_) {
      hasSpare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double factor = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * factor;
    hasSpare_ = true;
    return u * factor;
  }

  double normal(double mean, double stddev) { return mean + stddev * normal(); }

  // The whole engine state, for checkpoints.
  struct State {
    std::uint64_t words[4];
    bool hasSpare;
    double spare;
  };
  State state() const { return {{state_[0], state_[1], state_[2], state_[3]}, hasSpare_, spare_}; }
  void setState(const State& s) {
    for (int i = 0; i < 4; ++i) state_[i] = s.words[i];
    hasSpare_ = s.hasSpare;
    spare_ = s.spare;
  }

 private:
  static constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

  std::uint64_t state_[4];
  bool hasSpare_ = false;
  double spare_ = 0.0;
};

}  // namespace gpfd
