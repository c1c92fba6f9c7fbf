#include "gpfd/util/numpy_random.hpp"

namespace gpfd::numpy {
namespace {

// SeedSequence's hashing constants (bit_generator.pyx; after Melissa O'Neill's seed_seq_fe).
constexpr std::uint32_t kInitA = 0x43b0d7e5, kMultA = 0x931e8875;
constexpr std::uint32_t kInitB = 0x8b51f9dd, kMultB = 0x58f38ded;
constexpr std::uint32_t kMixMultL = 0xca01f9dd, kMixMultR = 0x4973f715;
constexpr int kXShift = 16;

std::uint32_t hashMix(std::uint32_t value, std::uint32_t& hashConst) {
  value ^= hashConst;
  hashConst *= kMultA;
  value *= hashConst;
  value ^= value >> kXShift;
  return value;
}

std::uint32_t mix(std::uint32_t x, std::uint32_t y) {
  std::uint32_t result = kMixMultL * x - kMixMultR * y;
  result ^= result >> kXShift;
  return result;
}

std::uint64_t rotateRight(std::uint64_t value, unsigned by) {
  return (value >> by) | (value << ((64 - by) & 63));
}

}  // namespace

SeedSequence::SeedSequence(std::span<const std::uint32_t> entropy) {
  std::uint32_t hashConst = kInitA;
  for (std::size_t i = 0; i < pool_.size(); ++i) {
    pool_[i] = hashMix(i < entropy.size() ? entropy[i] : 0, hashConst);
  }
  // Every pool word mixed with every other, so that late words reach early ones.
  for (std::size_t src = 0; src < pool_.size(); ++src) {
    for (std::size_t dst = 0; dst < pool_.size(); ++dst) {
      if (src != dst) pool_[dst] = mix(pool_[dst], hashMix(pool_[src], hashConst));
    }
  }
  // Entropy beyond the pool mixed into each pool word.
  for (std::size_t src = pool_.size(); src < entropy.size(); ++src) {
    for (auto& word : pool_) word = mix(word, hashMix(entropy[src], hashConst));
  }
}

std::vector<std::uint32_t> SeedSequence::generateState32(std::size_t words) const {
  std::vector<std::uint32_t> state(words);
  std::uint32_t hashConst = kInitB;
  for (std::size_t i = 0; i < words; ++i) {
    std::uint32_t value = pool_[i % pool_.size()];
    value ^= hashConst;
    hashConst *= kMultB;
    value *= hashConst;
    value ^= value >> kXShift;
    state[i] = value;
  }
  return state;
}

std::vector<std::uint64_t> SeedSequence::generateState64(std::size_t words) const {
  const std::vector<std::uint32_t> halves = generateState32(2 * words);
  std::vector<std::uint64_t> state(words);
  for (std::size_t i = 0; i < words; ++i) {
    state[i] = halves[2 * i] | (static_cast<std::uint64_t>(halves[2 * i + 1]) << 32);
  }
  return state;
}

std::vector<std::uint32_t> SeedSequence::wordsOf(std::uint64_t value) {
  std::vector<std::uint32_t> words{static_cast<std::uint32_t>(value)};
  if (value >> 32) words.push_back(static_cast<std::uint32_t>(value >> 32));
  return words;
}

Pcg64::Pcg64(const SeedSequence& seeds) {
  // _pcg64.pyx: four 64-bit words: the initial state (high, low), then the stream (high, low);
  // pcg64.h's srandom: increment = stream << 1 | 1, step, add the initial state, step.
  const std::vector<std::uint64_t> v = seeds.generateState64(4);
  const Uint128 initialState = (static_cast<Uint128>(v[0]) << 64) | v[1];
  const Uint128 stream = (static_cast<Uint128>(v[2]) << 64) | v[3];
  state_ = 0;
  increment_ = (stream << 1) | 1;
  step();
  state_ += initialState;
  step();
}

std::uint64_t Pcg64::next64() {
  step();
  const auto high = static_cast<std::uint64_t>(state_ >> 64);
  const auto low = static_cast<std::uint64_t>(state_);
  return rotateRight(high ^ low, static_cast<unsigned>(high >> 58));
}

std::array<std::uint64_t, 4> Pcg64::words() const {
  return {static_cast<std::uint64_t>(state_ >> 64), static_cast<std::uint64_t>(state_),
          static_cast<std::uint64_t>(increment_ >> 64), static_cast<std::uint64_t>(increment_)};
}

void Pcg64::setWords(const std::array<std::uint64_t, 4>& words) {
  state_ = (static_cast<Uint128>(words[0]) << 64) | words[1];
  increment_ = (static_cast<Uint128>(words[2]) << 64) | words[3];
}

}  // namespace gpfd::numpy
