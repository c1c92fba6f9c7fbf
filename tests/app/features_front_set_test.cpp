// `gpfd features show SET --front` on a set of runs (`gpfd evolve --runs N`): every run's front,
// each under a heading naming the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "../run/cli_helpers.hpp"
#include "gpfd/run/run_set.hpp"

namespace {

using gpfd::testing::freshDir;
using gpfd::testing::runGpfd;
using gpfd::testing::tinyEvolveConfig;

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(FeaturesFront, ShowsEveryRunOfASet) {
  const auto dir = freshDir("front-set");
  const auto evolve =
      runGpfd("evolve " + tinyEvolveConfig("front-set", 3) + " --runs 2 --quiet --out " + dir);
  ASSERT_EQ(evolve.status, 0) << evolve.output;

  const auto shown = runGpfd("features show " + dir + " --front");
  ASSERT_EQ(shown.status, 0) << shown.output;
  const auto first = runGpfd("features show " + dir + "/run-01 --front");
  const auto second = runGpfd("features show " + dir + "/run-02 --front");
  ASSERT_EQ(first.status, 0) << first.output;
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(shown.output, "run-01 (seed 3)\n" + first.output + "\nrun-02 (seed " +
                              std::to_string(gpfd::run::runSeed(3, 2)) + ")\n" + second.output);
  EXPECT_EQ(count(shown.output, "selection (mean +- SE)"), 2u) << shown.output;

  // A run not started yet says so; the others still show.
  std::filesystem::rename(dir + "/run-02", dir + "/run-02-moved");
  const auto partial = runGpfd("features show " + dir + " --front");
  EXPECT_EQ(partial.status, 0) << partial.output;
  EXPECT_NE(partial.output.find("run-02 (seed "), std::string::npos) << partial.output;
  EXPECT_NE(partial.output.find("not started"), std::string::npos) << partial.output;

  // Without --front a set has no single best.features: the error says what to give instead.
  const auto plain = runGpfd("features show " + dir);
  EXPECT_EQ(plain.status, 2);
  EXPECT_NE(plain.output.find("a set of runs"), std::string::npos) << plain.output;
}

}  // namespace
