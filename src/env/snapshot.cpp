#include "gpfd/env/snapshot.hpp"

#include <fmt/format.h>

#include <bit>
#include <limits>

#include "gpfd/env/environment.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

// FNV-1a, 64 bits (Fowler, Noll & Vo), of the format's name and the environment's.
std::uint64_t tagOf(const std::string& name) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : "gpfd snapshot 1 " + name) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

}  // namespace

SnapshotWriter::SnapshotWriter(const std::string& name) : words_{tagOf(name)} {}

SnapshotWriter& SnapshotWriter::word(std::uint64_t value) {
  words_.push_back(value);
  return *this;
}

SnapshotWriter& SnapshotWriter::integer(std::int64_t value) {
  return word(static_cast<std::uint64_t>(value));
}

SnapshotWriter& SnapshotWriter::real(double value) {
  return word(std::bit_cast<std::uint64_t>(value));
}

SnapshotWriter& SnapshotWriter::reals(std::span<const double> values) {
  word(values.size());
  for (const double v : values) real(v);
  return *this;
}

SnapshotWriter& SnapshotWriter::rng(const Rng& rng) {
  const Rng::State s = rng.state();
  for (const std::uint64_t w : s.words) word(w);
  word(s.hasSpare ? 1 : 0);
  return real(s.spare);
}

SnapshotWriter& SnapshotWriter::words(std::span<const std::uint64_t> values) {
  word(values.size());
  words_.insert(words_.end(), values.begin(), values.end());
  return *this;
}

SnapshotReader::SnapshotReader(const std::string& name, std::span<const std::uint64_t> words)
    : name_(name), words_(words) {
  if (words.empty() || words.front() != tagOf(name)) {
    throw InputError(fmt::format("not a snapshot of {}", name), where());
  }
}

std::string SnapshotReader::where() const { return name_ + " snapshot"; }

std::uint64_t SnapshotReader::word() {
  if (next_ >= words_.size()) {
    throw InputError(fmt::format("the snapshot ends after {} words", words_.size()), where());
  }
  return words_[next_++];
}

std::int64_t SnapshotReader::integer(std::int64_t lo, std::int64_t hi, const char* what) {
  const auto value = static_cast<std::int64_t>(word());
  if (value < lo || value > hi) {
    throw InputError(fmt::format("{} must be in [{}, {}], got {}", what, lo, hi, value), where());
  }
  return value;
}

double SnapshotReader::real() { return std::bit_cast<double>(word()); }

void SnapshotReader::reals(std::span<double> out) {
  const std::int64_t max = std::numeric_limits<std::int64_t>::max();
  const auto count = static_cast<std::size_t>(integer(0, max, "the number of values"));
  if (count != out.size()) {
    throw InputError(fmt::format("expected {} values, got {}", out.size(), count), where());
  }
  for (double& v : out) v = real();
}

Rng::State SnapshotReader::rng() {
  Rng::State s{};
  for (std::uint64_t& w : s.words) w = word();
  s.hasSpare = integer(0, 1, "the generator's spare flag") == 1;
  s.spare = real();
  return s;
}

std::span<const std::uint64_t> SnapshotReader::words() {
  const auto left = static_cast<std::int64_t>(words_.size() - std::min(next_, words_.size()));
  const auto count = static_cast<std::size_t>(integer(0, left - 1, "the number of words"));
  const auto out = words_.subspan(next_, count);
  next_ += count;
  return out;
}

void SnapshotReader::finish() const {
  if (next_ != words_.size()) {
    throw InputError(fmt::format("{} words left over", words_.size() - next_), where());
  }
}

std::vector<std::uint64_t> stateAndStepsSnapshot(const std::string& name,
                                                 std::span<const double> state, int steps) {
  return SnapshotWriter(name).reals(state).integer(steps).take();
}

void restoreStateAndSteps(const std::string& name, std::span<const std::uint64_t> words,
                          std::span<double> state, int& steps) {
  SnapshotReader in(name, words);
  std::vector<double> values(state.size());
  in.reals(values);
  const auto count = in.integer(0, std::numeric_limits<int>::max(), "the step count");
  in.finish();
  std::copy(values.begin(), values.end(), state.begin());
  steps = static_cast<int>(count);
}

void Environment::restore(std::span<const std::uint64_t> /*words*/) {
  throw InputError(fmt::format("{} has no snapshots", name()), name() + " snapshot");
}

}  // namespace gpfd::env
