// A simulation whose state becomes non-finite: during GP such an individual scores worst, even
// though its features (protected semantics) map the broken state to finite values; on the
// command line it is exit code 3 (simulate, train, assess), not success.
#include <gtest/gtest.h>

#include <cmath>

#include "../rl/test_envs.hpp"
#include "cli_helpers.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/expr/parse.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/run/learning_task.hpp"

namespace gpfd::testing {
namespace {

// The learners' test environments: a corridor (finite throughout) and one whose state turns to
// NaN after three steps.
const bool registered = [] {
  env::Registry::global().add({"corridor-test", "test", {}, [](const env::Params&) {
                                 return std::make_unique<rl::testing::Corridor>();
                               }});
  env::Registry::global().add({"poisoned-test", "test", {}, [](const env::Params&) {
                                 return std::make_unique<rl::testing::PoisonedEnv>();
                               }});
  return true;
}();

double fitnessOn(const std::string& env, const std::string& feature) {
  run::ExperimentConfig config;
  config.env = env;
  config.learnerParams = {{"updates", "3"}, {"episodes", "2"}};
  config.trials = 2;
  const run::LearningTask task(config, run::LearningTask::Budget::Trial);
  expr::Genome genome;
  genome.addFeature(expr::parseInfix(feature, task.stateNames()));
  Rng rng(1);
  return run::trialFitness(task, genome, rng);
}

TEST(NonFinite, AnIndividualWhoseSimulationBreaksScoresWorst) {
  ASSERT_TRUE(registered);
  EXPECT_TRUE(std::isfinite(fitnessOn("corridor-test", "x")));
  // The feature sanitises the broken state (NaN -> 0): still worst.
  EXPECT_EQ(fitnessOn("poisoned-test", "s"), -INFINITY);
  EXPECT_EQ(fitnessOn("poisoned-test", "sin(s) + 1"), -INFINITY);
  // The raw variables see it too.
  run::ExperimentConfig config;
  config.env = "poisoned-test";
  config.learnerParams = {{"updates", "3"}};
  const run::LearningTask task(config, run::LearningTask::Budget::Trial);
  Rng rng(2);
  const auto curve = task.train(features::RawFeatureMap(1), rng);
  EXPECT_TRUE(curve.diverged);
  EXPECT_EQ(task.score(curve), -INFINITY);
}

TEST(NonFinite, SimulateTrainAndAssessExitWithThree) {
  // The commands. simulate: a state that overflows at the first step.
  const auto simulate = runGpfd("simulate cartpole --state 0,0,0,1e300 --policy random --steps 3");
  EXPECT_EQ(simulate.status, 3) << simulate.output;
  EXPECT_EQ(simulate.output, "error: non-finite state at step 1: dx = -nan (cartpole)\n");
  // train: lambda-PI whose starting weights overflow every afterstate's value.
  std::string weights = "1e308";
  for (int i = 0; i < 18; ++i) weights += ",1e308";
  const auto dir = freshDir("train-diverged");
  const auto train = runGpfd("train tetris --param weights=" + weights +
                             " --param iterations=2 --param games=2 --quiet --out " + dir);
  EXPECT_EQ(train.status, 3) << train.output;
  EXPECT_EQ(train.output.rfind("error: training diverged", 0), 0u) << train.output;
  EXPECT_NE(readText(dir + "/weights.json").find("\"diverged\": true"), std::string::npos);
  // assess: the same learner settings, so every run of the original variables diverges (the
  // no-learning reference starts from zero: the weights are over the state); the results are
  // still written.
  const auto out = freshDir("assess-diverged");
  const auto assess =
      runGpfd("assess tetris --raw --runs 2 --budget 2 --param games=2 --param weights=" + weights +
              " --quiet --out " + out);
  EXPECT_EQ(assess.status, 3) << assess.output;
  EXPECT_NE(assess.output.find("error: 2 of 4 runs diverged"), std::string::npos) << assess.output;
  EXPECT_TRUE(std::filesystem::exists(out + "/summary.csv"));
}

}  // namespace
}  // namespace gpfd::testing
