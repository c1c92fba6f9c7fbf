#include "gpfd/env/gymnasium_twin.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <random>

#include "gpfd/env/snapshot.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

GymnasiumTwin::GymnasiumTwin(std::string id, std::size_t observationSize, TwinSettings settings,
                             ActionKind actionKind)
    : observation_(observationSize, 0.0),
      id_(std::move(id)),
      settings_(settings),
      actionKind_(actionKind) {
  for (std::size_t i = 0; i < observationSize; ++i) names_.push_back(fmt::format("x{}", i));
}

void GymnasiumTwin::reset(Rng& rng) { resetWithSeed(numpy::SeedSequence::wordsOf(rng() >> 1)); }

void GymnasiumTwin::resetWithSeed(std::span<const std::uint32_t> seedWords) {
  random_.emplace(numpy::SeedSequence(seedWords));
  elapsed_ = 0;
  start(*random_);
  roundObservation();
}

void GymnasiumTwin::resetWithoutSeed() {
  if (!random_) {
    // Gymnasium's np_random(None): SeedSequence of 128 bits of fresh entropy.
    std::random_device device;
    std::array<std::uint32_t, 4> entropy{};
    for (auto& word : entropy) word = device();
    random_.emplace(numpy::SeedSequence(entropy));
  }
  elapsed_ = 0;
  start(*random_);
  roundObservation();
}

StepResult GymnasiumTwin::stepAs(std::span<const double> action, ActionKind kind) {
  return stepWith(*this, action, kind);
}

void GymnasiumTwin::roundObservation() {
  for (double& value : observation_) value = numpy_scalar::toFloat32(value);
}

void GymnasiumTwin::checkActionSize(std::span<const double> action, std::size_t size) const {
  if (action.size() != size) {
    throw InputError(fmt::format("{} takes {} action component{}, got {}", id_, size,
                                 size == 1 ? "" : "s", action.size()),
                     id_ + " action");
  }
}

std::vector<std::uint64_t> GymnasiumTwin::snapshot() const {
  SnapshotWriter writer(id_);
  writer.word(random_ ? 1 : 0);
  if (random_) {
    const auto words = random_->words();
    writer.words(words);
  }
  writer.integer(elapsed_).reals(dynamics_).word(extra_).reals(observation_);
  return writer.take();
}

void GymnasiumTwin::restore(std::span<const std::uint64_t> words) {
  SnapshotReader reader(id_, words);
  std::optional<numpy::Pcg64> random;
  if (reader.word() != 0) {
    const auto stream = reader.words();
    if (stream.size() != 4) throw InputError("a PCG64 state is 4 words", id_ + " snapshot");
    random.emplace(numpy::SeedSequence(std::array<std::uint32_t, 1>{0}));
    random->setWords({stream[0], stream[1], stream[2], stream[3]});
  }
  const auto elapsed = static_cast<int>(reader.integer(0, 1000000000, "elapsed steps"));
  std::vector<double> dynamics(dynamics_.size()), observation(observation_.size());
  reader.reals(dynamics);
  const std::uint64_t extra = reader.word();
  reader.reals(observation);
  reader.finish();
  random_ = random;
  elapsed_ = elapsed;
  dynamics_ = std::move(dynamics);
  extra_ = extra;
  observation_ = std::move(observation);
}

}  // namespace gpfd::env
