// The seeds of a set of runs survive the config text stored in every checkpoint: TOML integers are
// signed 64-bit, and derived seeds are often 2^63 or above (resuming run 2 of `evolve --runs` once
// failed on one).
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "gpfd/run/experiment_config.hpp"
#include "gpfd/run/run_set.hpp"

namespace gpfd::run {
namespace {

TEST(RunSeed, EverySeedRoundTripsThroughTheConfigText) {
  const std::uint64_t big = std::numeric_limits<std::uint64_t>::max();
  for (const std::uint64_t seed : {std::uint64_t{0}, std::uint64_t{1}, runSeed(1, 2), runSeed(1, 3),
                                   std::uint64_t{1} << 63, big}) {
    ExperimentConfig config;
    config.env = "cartpole";
    config.seed = seed;
    const auto text = formatExperimentConfig(config);
    EXPECT_EQ(parseExperimentConfig(text, "test").seed, seed) << text;
  }
  EXPECT_GE(runSeed(1, 2), std::uint64_t{1} << 63);  // The case that failed.
}

}  // namespace
}  // namespace gpfd::run
