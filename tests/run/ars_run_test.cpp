// The ars learner wherever a learner is used: `gpfd learners` lists it, a config with
// `[learner] name = "ars"` and a choice of its settings (learner.choose) runs `gpfd evolve` to the
// same results on one and two threads, `gpfd assess` trains it on that run's config, and the
// trials of a fitness evaluation (compiled features, lanes of several trials) are what training
// each alone gives, on each quick config's environment.
#include <gtest/gtest.h>

#include <cmath>

#include "../rl/same_curves.hpp"
#include "cli_helpers.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/run/experiment_config.hpp"
#include "gpfd/run/learning_task.hpp"

namespace gpfd::testing {
namespace {

// A tiny cart-pole run with ARS, choosing its step size.
std::string arsConfig() {
  return writeText("ars.toml", R"(name = "ars"
seed = 5
[env]
name = "cartpole"
params = { actions = "discrete", max_steps = 200 }
[learner]
name = "ars"
params = { updates = 3, n_delta = 4, n_top = 2 }
choose = { learning_rate = ["0.02", "0.1"] }
choose_seeds = 3
[fitness]
trials = 2
[genome]
max_features = 3
max_depth = 3
max_size = 9
[gp]
population = 6
generations = 2
[validation]
candidates = 3
seeds = 4
confirm_seeds = 6
confirm_params = { updates = 5 }
)");
}

std::string fingerprint(const std::string& dir) {
  return withoutSeconds(readText(dir + "/generations.csv")) + readText(dir + "/best.features") +
         readText(dir + "/validation.csv");
}

TEST(ArsRun, IsListedWithItsParameters) {
  const auto learners = runGpfd("learners");
  ASSERT_EQ(learners.status, 0);
  EXPECT_NE(learners.output.find("ars: Augmented Random Search"), std::string::npos)
      << learners.output;
  EXPECT_NE(learners.output.find("n_delta = 8"), std::string::npos) << learners.output;
}

TEST(ArsRun, EvolveChoosesItsSettingsAndIsTheSameOnOneAndTwoThreads) {
  const auto one = freshDir("ars-t1"), two = freshDir("ars-t2");
  const auto a = runGpfd("evolve " + arsConfig() + " --quiet --threads 1 --out " + one);
  ASSERT_EQ(a.status, 0) << a.output;
  const auto b = runGpfd("evolve " + arsConfig() + " --quiet --threads 2 --out " + two);
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_EQ(fingerprint(one), fingerprint(two));
  const auto written = run::loadExperimentConfig(one + "/config.toml");
  EXPECT_EQ(written.learner, "ars");
  EXPECT_TRUE(written.learnerChoices.empty());
  const auto rate = written.learnerParams.at("learning_rate");
  EXPECT_TRUE(rate == "0.02" || rate == "0.1") << rate;
  EXPECT_NE(readText(one + "/best.features").find("# env: cartpole"), std::string::npos);
  // gpfd assess trains ARS with that run's config.
  const auto dir = freshDir("ars-assess");
  const auto features = writeText("ars.features", "# env: cartpole\nx + th\n");
  const auto assessed = runGpfd("assess --config " + one + "/config.toml --features " + features +
                                " --runs 2 --budget 4 --threads 2 --quiet --out " + dir);
  ASSERT_EQ(assessed.status, 0) << assessed.output;
  EXPECT_NE(readText(dir + "/summary.csv").find("original"), std::string::npos);
}

// The shipped config with ARS in the loop (configs/user-env-ars.toml) on a twin of Gymnasium's
// task: it chooses V1 or V2 on the task and runs the whole protocol with ARS.
TEST(ArsRun, TheShippedUserEnvArsConfigRunsWithArsInTheLoop) {
  const auto dir = freshDir("user-env-ars");
  const auto run = runGpfd("evolve user-env-ars --env Pendulum-v1 --population 4 --generations 1 " +
                           std::string("--seed 2 --threads 2 --quiet --out ") + dir);
  ASSERT_EQ(run.status, 0) << run.output;
  const auto written = run::loadExperimentConfig(dir + "/config.toml");
  EXPECT_EQ(written.learner, "ars");
  EXPECT_EQ(written.env, "Pendulum-v1");
  EXPECT_TRUE(written.learnerChoices.empty());
  const auto normalise = written.learnerParams.at("normalise");
  EXPECT_TRUE(normalise == "false" || normalise == "true") << normalise;
  EXPECT_EQ(written.learnerParams.at("greedy_last"), "true");
  EXPECT_NE(readText(dir + "/confirmation.csv").find("original"), std::string::npos);
}

TEST(ArsRun, TrialsTogetherEqualEachTrialAloneOnTheQuickConfigsEnvironments) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"cartpole", "x\nsin(th) * dth\ncos(th)\n"},
      {"acrobot", "sin(th1)\ncos(th2)\ndth1 + dth2\n"},
      {"swimmer3", "dGx\nsin(th1) + dth2\n"}};
  for (const auto& [name, features] : cases) {
    for (const bool normalise : {false, true}) {
      SCOPED_TRACE(name + (normalise ? " V2" : " V1"));
      run::ExperimentConfig config = run::loadExperimentConfig(std::string(GPFD_SOURCE_DIR) +
                                                               "/configs/" + name + "-quick.toml");
      config.learner = "ars";
      config.learnerChoices.clear();
      config.learnerAlternatives.clear();
      config.learnerParams = {{"updates", "4"},
                              {"n_delta", "3"},
                              {"normalise", normalise ? "true" : "false"},
                              {"max_episode_steps", "300"}};
      const run::LearningTask task(config, run::LearningTask::Budget::Trial);
      const auto genome =
          expr::parseFeaturesFile(features, "test", task.stateNames(), config.env).genome;
      const auto map = task.featureMap(genome);
      std::vector<Rng> rngs{Rng(11), Rng(12), Rng(13)};
      const auto curves = task.trainRuns(*map, rngs);
      ASSERT_EQ(curves.size(), 3u);
      for (std::size_t k = 0; k < 3; ++k) {
        Rng alone(11 + k);
        const auto curve = task.train(*map, alone);
        EXPECT_FALSE(curve.diverged) << curve.divergedReason;
        EXPECT_EQ(curve.points.size(), 5u);
        rl::testing::expectSameCurves(curves[k], curve);
        EXPECT_EQ(rngs[k](), alone());
      }
      Rng a(7), b(7);
      const double fitness = run::trialFitness(task, genome, a);
      EXPECT_TRUE(std::isfinite(fitness));
      EXPECT_EQ(fitness, run::trialFitness(task, genome, b));
    }
  }
}

}  // namespace
}  // namespace gpfd::testing
