// `gpfd evolve` with successive halving (fitness.promote): the run is the same on one and two
// threads, resumes exactly, and its time budget counts the longer rungs.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_helpers.hpp"

namespace gpfd::testing {
namespace {

const std::string kHalving =
    " --set fitness.promote=0.34 --set fitness.rung_params.updates=6 --set "
    "validation.confirm_params.updates=8 --set validation.candidates=3 --set "
    "validation.seeds=4 --set validation.confirm_seeds=4 --set validation.confirm_looks=1";

std::string fingerprint(const std::string& dir) {
  return withoutSeconds(readText(dir + "/generations.csv")) + readText(dir + "/best.features");
}

TEST(SuccessiveHalvingRun, IsTheSameOnOneAndTwoThreadsAndDiffersFromAPlainRun) {
  const auto config = tinyEvolveConfig("halving", 3);
  const auto one = freshDir("halving-t1"), two = freshDir("halving-t2"), plain = freshDir("plain");
  const auto r = runGpfd("evolve " + config + kHalving + " --threads 1 --out " + one);
  ASSERT_EQ(r.status, 0) << r.output;
  // 12 individuals: ceil(0.34 x 12) = 5 at the middle rung, ceil(0.34 x 5) = 2 of them at the last.
  EXPECT_NE(r.output.find("7 at longer rungs"), std::string::npos) << r.output;
  ASSERT_EQ(runGpfd("evolve " + config + kHalving + " --quiet --threads 2 --out " + two).status, 0);
  EXPECT_EQ(fingerprint(one), fingerprint(two));
  // The longest rung's fitness is in the population, and selection used it.
  EXPECT_NE(readText(one + "/checkpoint.json").find("\"rung\": 2"), std::string::npos);
  const auto withoutHalving = kHalving.substr(kHalving.find(" --set validation.confirm_params"));
  ASSERT_EQ(runGpfd("evolve " + config + withoutHalving + " --quiet --out " + plain).status, 0);
  EXPECT_NE(fingerprint(one), fingerprint(plain));
}

TEST(SuccessiveHalvingRun, AnExtendedResumeMatchesALongerRun) {
  const auto config = tinyEvolveConfig("halving-resume", 4);
  const auto longer = freshDir("halving-8");
  ASSERT_EQ(
      runGpfd("evolve " + config + kHalving + " --quiet --generations 8 --out " + longer).status,
      0);
  const auto dir = freshDir("halving-6-then-8");
  ASSERT_EQ(runGpfd("evolve " + config + kHalving + " --quiet --out " + dir).status, 0);
  const auto resumed = runGpfd("evolve --quiet --resume " + dir + " --generations 8");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_EQ(fingerprint(dir), fingerprint(longer));
}

TEST(SuccessiveHalvingRun, ATimeBudgetMeasuresTheRungs) {
  const auto dir = freshDir("halving-budget");
  const auto r = runGpfd("evolve " + tinyEvolveConfig("halving-budget", 5) + kHalving +
                         " --time-budget 20 --quiet --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const auto run = nlohmann::json::parse(readText(dir + "/run.json"));
  EXPECT_GT(run.at("time_budget").at("measured").at("rung_evaluations").get<double>(), 0.0);
}

}  // namespace
}  // namespace gpfd::testing
