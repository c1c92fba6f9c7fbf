// A simulation whose state becomes non-finite: during GP such an individual scores worst, even
// though its features (protected semantics) map the broken state to finite values; on the
// command line it is exit code 3 (simulate, train, assess), not success.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_helpers.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/expr/parse.hpp"
#include "gpfd/jit/feature_map.hpp"
#include "gpfd/run/learning_task.hpp"

namespace gpfd::testing {
namespace {

// One variable multiplied by `growth` at every step: with a growth of 1e200 it overflows to inf
// at the second step, and inf - inf then gives NaN.
class Growing final : public env::Environment {
 public:
  explicit Growing(double growth) : growth_(growth) {}
  std::string name() const override { return "growing"; }
  env::Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  env::ActionSpace actionSpace() const override {
    env::ActionSpace space;
    space.kind = env::ActionSpace::Kind::Discrete;
    space.choices = 2;
    space.names = {"a"};
    return space;
  }
  void reset(Rng& rng) override {
    s_ = rng.uniform(0.5, 1.0);
    steps_ = 0;
  }
  std::span<const double> state() const override { return {&s_, 1}; }
  void setState(std::span<const double> state) override { s_ = state[0]; }
  env::StepResult step(std::span<const double> action) override {
    s_ = s_ * growth_ - (s_ * growth_ - s_) * action[0];
    return {-1.0, false, ++steps_ == 50};
  }

 private:
  double growth_;
  double s_ = 1.0;
  int steps_ = 0;
  std::vector<std::string> names_{"s"};
};

const bool registered = [] {
  for (double growth : {1.0, 1e200}) {
    const std::string name = growth == 1.0 ? "steady-test" : "exploding-test";
    env::Registry::global().add({name, "test", {}, [growth](const env::Params&) {
                                   return std::make_unique<Growing>(growth);
                                 }});
  }
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
  EXPECT_EQ(fitnessOn("steady-test", "s"), -50.0);
  // The feature sanitises the broken state (NaN -> 0, inf -> DBL_MAX): still worst.
  EXPECT_EQ(fitnessOn("exploding-test", "s"), -INFINITY);
  EXPECT_EQ(fitnessOn("exploding-test", "sin(s) + 1"), -INFINITY);
  // The raw variables see it too.
  run::ExperimentConfig config;
  config.env = "exploding-test";
  config.learnerParams = {{"updates", "3"}};
  const run::LearningTask task(config, run::LearningTask::Budget::Trial);
  Rng rng(2);
  const auto curve = task.train(jit::RawFeatureMap(1), rng);
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
  // assess: the same learner settings, so every run diverges; the results are still written.
  const auto out = freshDir("assess-diverged");
  const auto assess =
      runGpfd("assess tetris --raw --runs 2 --budget 2 --param games=2 --param weights=" + weights +
              " --quiet --out " + out);
  EXPECT_EQ(assess.status, 3) << assess.output;
  EXPECT_NE(assess.output.find("error: 2 of 2 runs diverged"), std::string::npos) << assess.output;
  EXPECT_TRUE(std::filesystem::exists(out + "/summary.csv"));
}

}  // namespace
}  // namespace gpfd::testing
