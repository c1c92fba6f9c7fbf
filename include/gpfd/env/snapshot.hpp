// env: snapshots, an environment's whole dynamic state as 64-bit words (Environment::snapshot),
// and the writer and reader that environments build theirs with. A double is stored as its bits,
// so that a restored environment continues bit for bit. Python pickles gpfd's environments with
// them (python/src/env_state_bindings.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpfd/util/rng.hpp"

namespace gpfd::env {

// Appends words in the order of the calls. The first word is a tag made from the name given (an
// environment's name()), so that a snapshot is never read as another environment's.
class SnapshotWriter {
 public:
  explicit SnapshotWriter(const std::string& name);

  SnapshotWriter& word(std::uint64_t value);
  SnapshotWriter& integer(std::int64_t value);
  SnapshotWriter& real(double value);
  SnapshotWriter& reals(std::span<const double> values);
  SnapshotWriter& rng(const Rng& rng);
  SnapshotWriter& words(std::span<const std::uint64_t> values);  // Its length, then the words.

  std::vector<std::uint64_t> take() { return std::move(words_); }

 private:
  std::vector<std::uint64_t> words_;
};

// Reads a SnapshotWriter's words back in the same order. InputError (where: "NAME snapshot") for
// words of another name, too few words, an integer out of its range, or words left at finish().
class SnapshotReader {
 public:
  SnapshotReader(const std::string& name, std::span<const std::uint64_t> words);

  std::uint64_t word();
  std::int64_t integer(std::int64_t lo, std::int64_t hi, const char* what);
  double real();
  void reals(std::span<double> out);  // Exactly out.size() values.
  Rng::State rng();
  std::span<const std::uint64_t> words();  // What SnapshotWriter::words wrote.
  void finish() const;

 private:
  std::string where() const;

  std::string name_;
  std::span<const std::uint64_t> words_;
  std::size_t next_ = 1;
};

// The snapshot of an environment whose dynamic state is its state variables and its episode's
// step count (cart-pole, Acrobot, the swimmer), and its reading into `state` (of the size written)
// and `steps`; on an InputError nothing is written.
std::vector<std::uint64_t> stateAndStepsSnapshot(const std::string& name,
                                                 std::span<const double> state, int steps);
void restoreStateAndSteps(const std::string& name, std::span<const std::uint64_t> words,
                          std::span<double> state, int& steps);

}  // namespace gpfd::env
