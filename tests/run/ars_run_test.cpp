// The ars learner wherever a learner is used: `gpfd learners` lists it, a config with
// `[learner] name = "ars"` and a choice of its settings (learner.choose) runs `gpfd evolve` to the
// same results on one and two threads, and `gpfd assess` trains it on that run's config.
#include <gtest/gtest.h>

#include "cli_helpers.hpp"
#include "gpfd/run/experiment_config.hpp"

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

}  // namespace
}  // namespace gpfd::testing
