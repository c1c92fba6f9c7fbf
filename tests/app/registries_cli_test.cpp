// The registries from the command line: environments and learners listed with their defaults and
// ranges, parameters refused by name and range (exit 2), and the learner's budget parameter and
// the environment's default learner used by the commands.
#include <gtest/gtest.h>

#include <string>

#include "../run/cli_helpers.hpp"

namespace {

using gpfd::testing::freshDir;
using gpfd::testing::readText;
using gpfd::testing::runGpfd;

TEST(RegistriesCli, ListsEnvironmentsAndLearnersFromTheirDeclarations) {
  const auto envs = runGpfd("envs");
  ASSERT_EQ(envs.status, 0);
  EXPECT_NE(envs.output.find("dt = 0.2  in [0.0001, 10]: control interval"), std::string::npos)
      << envs.output;
  EXPECT_NE(envs.output.find("default learner: lpi; typical state ranges: unknown"),
            std::string::npos);
  const auto learners = runGpfd("learners");
  ASSERT_EQ(learners.status, 0);
  EXPECT_NE(learners.output.find("pg: policy gradient"), std::string::npos);
  EXPECT_NE(learners.output.find("budget: iterations"), std::string::npos);
  EXPECT_NE(learners.output.find("updates = 100  in [0, 1000000]"), std::string::npos);
  EXPECT_NE(runGpfd("train --help").output.find("pg: updates, episodes"), std::string::npos);
}

TEST(RegistriesCli, ParametersOutOfRangeAreRefusedByNameAndRange) {
  const auto dt = runGpfd("simulate acrobot --param dt=1e300 --policy random --steps 3");
  EXPECT_EQ(dt.status, 2);
  EXPECT_NE(dt.output.find("error: dt must lie in [0.0001, 10], got 1e300 (acrobot.dt)"),
            std::string::npos)
      << dt.output;
  EXPECT_EQ(dt.output.find("nan"), std::string::npos);
  const auto dir = freshDir("registries-cli");
  const auto segments = runGpfd("train swimmer --param segments=1000 --out " + dir);
  EXPECT_EQ(segments.status, 2);
  EXPECT_NE(segments.output.find("segments must lie in [2, 100], got 1000 (swimmer.segments)"),
            std::string::npos)
      << segments.output;
  const auto updates = runGpfd("train cartpole --param updates=abc --out " + dir);
  EXPECT_EQ(updates.status, 2);
  EXPECT_NE(updates.output.find("'abc' is not an integer (pg.updates)"), std::string::npos)
      << updates.output;
  EXPECT_EQ(runGpfd("train cartpole --learner sarsa --out " + dir).status, 2);
  EXPECT_EQ(runGpfd("train tetris --learner pg --out " + dir).status, 2);
}

TEST(RegistriesCli, AssessSetsTheLearnersBudgetParameter) {
  const auto dir = freshDir("registries-cli-assess");
  const auto r = runGpfd(
      "assess tetris --raw --budget 1 --runs 2 --param games=2 "
      "--param max_moves=30 --threads 1 --quiet --out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  // The default learner of tetris (lpi): one iteration, so rows 0 and 1 of each curve.
  const std::string curves = readText(dir + "/curves.csv");
  EXPECT_NE(curves.find("\noriginal,1,"), std::string::npos) << curves;
  EXPECT_EQ(curves.find("\noriginal,2,"), std::string::npos) << curves;
}

}  // namespace
