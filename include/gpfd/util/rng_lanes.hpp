// util: the engines of many independent random streams side by side (structure of arrays), and
// standard normal draws from all of them at once: xoshiro256** and the ziggurat's fast path four
// lanes at a time with AVX2 (integer shifts and adds; the 53-bit uniform converted exactly), the
// rare draws outside the rectangles lane by lane. Lane l draws exactly what standardNormal (util/
// ziggurat.hpp) draws from the Rng put into lane l, so lockstep learners can give each episode
// its own stream and still match the sequential reference bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gpfd/util/rng.hpp"

namespace gpfd {

class RngLanes {
 public:
  explicit RngLanes(std::size_t lanes);

  std::size_t lanes() const { return lanes_; }
  // Puts the state of `rng` into lane `lane` (its spare normal, if any, is not carried: the
  // ziggurat keeps none). Reads it back.
  void set(std::size_t lane, const Rng& rng);
  Rng get(std::size_t lane) const;
  void move(std::size_t from, std::size_t to);  // Lane `to` takes lane `from`'s state.

  // out[l] = standardNormal of lane l, for lanes [0, n), n <= lanes(). With `avx2` (only where
  // cpuHasAvx2()), full groups of four lanes go through the AVX2 path, the rest one by one.
  void standardNormal(std::size_t n, double* out, bool avx2);

 private:
  std::size_t lanes_, stride_;
  std::vector<std::uint64_t> words_;  // Word w of lane l at words_[w * stride_ + l].
};

}  // namespace gpfd
