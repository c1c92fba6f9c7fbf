// The no-learning reference end to end: a task on which the learner harms (it does worse on the
// original variables than a policy that ignores the state), named as such in best.features, the
// tables and the text; a winner that only beats such a learner is not returned as a discovery.
#include <gtest/gtest.h>

#include <algorithm>

#include "cli_helpers.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/service/assess.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/service/evolve_text.hpp"

namespace gpfd::testing {
namespace {

// A one-step bandit whose best action is 0 whatever the state: state s ~ U(-100, 100), action a
// clipped to [-1, 1], reward -a^2. Policy gradient's default Rprop steps (0.1 at first, never
// below 0.01) on the weight of s move the action by up to 10, so on the original variables it
// does far worse than with only its bias, which needs no state at all.
class Overshoot final : public env::Environment {
 public:
  std::string name() const override { return "overshoot-test"; }
  env::Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  env::ActionSpace actionSpace() const override {
    env::ActionSpace space;
    space.low = {-1.0};
    space.high = {1.0};
    return space;
  }
  void reset(Rng& rng) override { s_ = rng.uniform(-100.0, 100.0); }
  std::span<const double> state() const override { return {&s_, 1}; }
  void setState(std::span<const double> state) override { s_ = state[0]; }
  env::StepResult step(std::span<const double> action) override {
    const double a = std::clamp(action[0], -1.0, 1.0);
    return {-a * a, true, false};
  }

 private:
  double s_ = 0.0;
  std::vector<std::string> names_{"s"};
};

const bool registered = [] {
  env::Registry::global().add({"overshoot-test", "test", {}, [](const env::Params&) {
                                 return std::make_unique<Overshoot>();
                               }});
  return true;
}();

std::string overshootConfig() {
  return writeText("overshoot.toml", R"(name = "overshoot"
seed = 3
[env]
name = "overshoot-test"
[learner]
name = "pg"
params = { updates = 10, episodes = 10 }
[fitness]
trials = 2
[genome]
max_features = 2
max_depth = 3
max_size = 7
[gp]
population = 10
generations = 2
[validation]
candidates = 3
seeds = 10
confirm_seeds = 12
confirm_params = { updates = 10 }
)");
}

std::string lastLine(const std::string& text) {
  const auto end = text.find_last_not_of('\n');
  return text.substr(text.rfind('\n', end) + 1, end - text.rfind('\n', end));
}

TEST(NoLearning, AHarmfulLearnerIsNamedAndNoBetterThanNoLearningIsNoDiscovery) {
  ASSERT_TRUE(registered);
  const auto dir = freshDir("no-learning-evolve");
  service::EvolveRequest request;
  request.config = overshootConfig();
  request.out = {dir, false, "--out"};
  request.threads = 2;
  std::string text;
  service::EvolveText progress(
      {[&](const std::string& s) { text += s; }, [&](const std::string& s) { text += s; }});
  const std::atomic<bool> stop{false};
  ASSERT_TRUE(service::evolve(request, progress, stop).finished);

  EXPECT_EQ(lastLine(readText(dir + "/validation.csv")).rfind(",no-learning,", 0), 0u);
  const auto confirmation = readText(dir + "/confirmation.csv");
  EXPECT_EQ(lastLine(confirmation).rfind("no-learning,", 0), 0u) << confirmation;
  const auto best = readText(dir + "/best.features");
  EXPECT_NE(best.find("# no_learning: "), std::string::npos) << best;
  EXPECT_NE(best.find("# warning: the learner harms: on the original variables it does worse "
                      "than no learning"),
            std::string::npos)
      << best;
  EXPECT_NE(text.find("warning: the learner harms"), std::string::npos) << text;
  // Whatever GP found beat the harmful learner but not a policy that ignores the state: the
  // original variables are returned, and the verdict says why.
  EXPECT_NE(best.find("# verdict: the validation winner is not significantly better than no "
                      "learning"),
            std::string::npos)
      << best;
  EXPECT_NE(best.find("not a discovery; these are the original variables"), std::string::npos);
  EXPECT_NE(text.find("not a discovery"), std::string::npos) << text;
}

TEST(NoLearning, AssessmentsTrainItAsTheLastRow) {
  ASSERT_TRUE(registered);
  service::AssessRequest request;
  request.env = "overshoot-test";
  request.raw = true;
  request.runs = 6;
  request.budget = 10;
  const auto dir = freshDir("no-learning-assess");
  request.out = {dir, false, "--out"};
  const auto result = service::assess(request);
  EXPECT_EQ(lastLine(readText(dir + "/summary.csv")).rfind("no-learning,6,", 0), 0u);
  ASSERT_EQ(result.summary.size(), 2u);
  EXPECT_EQ(result.summary[0].name, "original");
  EXPECT_EQ(result.summary[1].name, "no-learning");
  // The learner harms here: the original variables end far below no learning.
  EXPECT_LT(result.summary[0].final.mean, result.summary[1].final.mean);
  EXPECT_LT(result.summary[1].vsBaseline.welchP, 0.05)
      << result.summary[0].final.mean << " " << result.summary[1].final.mean;
  EXPECT_EQ(result.runs, 12);
}

}  // namespace
}  // namespace gpfd::testing
