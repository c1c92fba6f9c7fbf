// Policy gradient with the episodes of an update played in lockstep (through the batched
// environments) gives the same curves, weights, evaluations and gradient estimates, bit for bit,
// as the sequential reference: on every batched environment, with compiled and raw features,
// Gaussian and softmax policies, normalisation, a learned std, caps and a run that diverges; and
// on environments without a batched form, whose copies the lockstep player steps lane by lane.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "gpfd/env/batch.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/rl/policy_gradient.hpp"
#include "gpfd/run/learning_task.hpp"
#include "same_curves.hpp"
#include "unbatched_cartpole.hpp"

namespace gpfd::rl {
namespace {

using testing::expectSameCurves;
using testing::sameBits;

using gpfd::testing::UnbatchedCartPole;

void registerCountedCartPole() {
  gpfd::testing::registerUnbatchedCartPole("counted-cartpole");
  gpfd::testing::registerUnbatchedCartPole("uncopyable-cartpole", false);
}

struct Setting {
  std::string name;
  std::string env;
  env::Params envParams;
  std::string features;  // A features file over the state variables; empty: the raw variables.
  std::vector<std::pair<std::string, std::string>> learner;
};

std::vector<Setting> settings() {
  registerCountedCartPole();
  return {
      {"cartpole raw", "cartpole", {{"max_steps", "200"}}, "", {}},
      {"cartpole compiled",
       "cartpole",
       {{"max_steps", "200"}},
       "sin(th)\ndth * cos(th)\nx + dx\n",
       {}},
      {"cartpole softmax normalised",
       "cartpole",
       {{"actions", "discrete"}, {"max_steps", "150"}},
       "",
       {{"normalise", "true"}}},
      {"acrobot",
       "acrobot",
       {{"max_steps", "120"}},
       "sin(th1)\ncos(th2)\ndth1\ndth2 - dth1\n",
       {{"std", "1.0"}}},
      {"acrobot discrete, learned std unused",
       "acrobot",
       {{"actions", "discrete"}, {"max_steps", "80"}},
       "",
       {{"bias", "false"}}},
      {"swimmer3 learned std",
       "swimmer",
       {{"segments", "3"}, {"horizon", "40"}},
       "",
       {{"learn_std", "true"}, {"discount", "0.97"}}},
      {"swimmer3 greedy last row",
       "swimmer",
       {{"segments", "3"}, {"horizon", "40"}},
       "",
       {{"learn_std", "true"}, {"greedy_last", "true"}}},
      {"swimmer5 normalised",
       "swimmer",
       {{"segments", "5"}, {"horizon", "30"}},
       "sin(th1)\nth5\ndth2\ndGx\n",
       {{"normalise", "true"}, {"max_episode_steps", "25"}}},
      // Lane by lane (no batched form):
      {"counted cartpole compiled",
       "counted-cartpole",
       {{"max_steps", "200"}},
       "sin(th)\ndth * cos(th)\nx + dx\n",
       {}},
      {"counted cartpole softmax normalised",
       "counted-cartpole",
       {{"actions", "discrete"}, {"max_steps", "150"}},
       "",
       {{"normalise", "true"}}},
      {"swimmer9 learned std",
       "swimmer",
       {{"segments", "9"}, {"horizon", "30"}},
       "",
       {{"learn_std", "true"}}},
  };
}

std::shared_ptr<const features::FeatureMap> featureMap(const Setting& s,
                                                       const env::Environment& environment) {
  if (s.features.empty()) return std::make_shared<features::RawFeatureMap>(environment.stateDim());
  const auto file =
      expr::parseFeaturesFile(s.features, "test", environment.stateNames(), environment.name());
  return std::make_shared<jit::CompiledFeatureMap>(file.genome, environment.stateDim());
}

PolicyGradientConfig config(const Setting& s, bool lockstep) {
  PolicyGradientConfig c;
  c.updates = 6;
  for (const auto& [k, v] : s.learner) EXPECT_TRUE(policyGradientParams().apply(c, k, v)) << k;
  c.lockstep = lockstep;
  return c;
}

TEST(Lockstep, TrainingCurvesEqualTheSequentialReference) {
  for (const Setting& s : settings()) {
    SCOPED_TRACE(s.name);
    const auto environment = env::Registry::global().make(s.env, s.envParams);
    const auto map = featureMap(s, *environment);
    Rng a(77), b(77);
    const LearningCurve lockstep = trainPolicyGradient(*environment, *map, config(s, true), a);
    const LearningCurve sequential = trainPolicyGradient(*environment, *map, config(s, false), b);
    ASSERT_FALSE(sequential.diverged) << sequential.divergedReason;
    EXPECT_GT(sequential.steps, 100);
    expectSameCurves(lockstep, sequential);
    EXPECT_EQ(a(), b());  // Both drew the same from the caller's engine.
  }
}

TEST(Lockstep, EvaluationsAndGradientEstimatesEqualTheSequentialReference) {
  for (const Setting& s : settings()) {
    SCOPED_TRACE(s.name);
    const auto environment = env::Registry::global().make(s.env, s.envParams);
    const auto map = featureMap(s, *environment);
    Rng train(5);
    const LearningCurve curve = trainPolicyGradient(*environment, *map, config(s, false), train);
    for (const bool greedy : {true, false}) {
      Rng a(9), b(9);
      // 70 episodes: more than one call of a player (64 lanes at most).
      const EvaluationResult x =
          evaluatePolicy(*environment, *map, curve.weights, config(s, true), 70, greedy, a);
      const EvaluationResult y =
          evaluatePolicy(*environment, *map, curve.weights, config(s, false), 70, greedy, b);
      EXPECT_EQ(x.episodes, 70);
      EXPECT_EQ(x.episodes, y.episodes);
      EXPECT_EQ(x.steps, y.steps);
      EXPECT_TRUE(sameBits(x.meanReturn, y.meanReturn)) << x.meanReturn << " vs " << y.meanReturn;
      EXPECT_TRUE(sameBits(x.stdReturn, y.stdReturn));
    }
    if (s.learner.empty()) {
      Eigen::VectorXd parameters(static_cast<Eigen::Index>(curve.weights.values.size()));
      for (Eigen::Index i = 0; i < parameters.size(); ++i) {
        parameters[i] =
            curve.weights.values[static_cast<std::size_t>(i)] + 0.01 * static_cast<double>(i % 3);
      }
      Rng a(11), b(11);
      const Eigen::VectorXd x =
          estimatePolicyGradient(*environment, *map, config(s, true), parameters, 13, a);
      const Eigen::VectorXd y =
          estimatePolicyGradient(*environment, *map, config(s, false), parameters, 13, b);
      ASSERT_EQ(x.size(), y.size());
      for (Eigen::Index i = 0; i < x.size(); ++i) EXPECT_TRUE(sameBits(x[i], y[i])) << i;
    }
  }
}

// Several runs together (the trials of a fitness evaluation) give each run's own curve: the same
// as training it alone, sequentially, whatever the other runs do (some diverge or stop early).
TEST(Lockstep, RunsTogetherEqualRunsAlone) {
  for (const Setting& s : settings()) {
    SCOPED_TRACE(s.name);
    const auto environment = env::Registry::global().make(s.env, s.envParams);
    const auto map = featureMap(s, *environment);
    for (const bool lockstep : {true, false}) {
      PolicyGradientConfig c = config(s, lockstep);
      c.maxTotalSteps = 600;  // Runs stop after different updates.
      std::vector<Rng> together;
      for (std::uint64_t k = 0; k < 7; ++k) together.emplace_back(100 + k);
      const std::vector<LearningCurve> curves =
          trainPolicyGradientRuns(*environment, *map, c, together);
      ASSERT_EQ(curves.size(), 7u);
      std::size_t lengths = 0;
      for (std::uint64_t k = 0; k < 7; ++k) {
        Rng alone(100 + k);
        const LearningCurve reference =
            trainPolicyGradient(*environment, *map, config(s, false), alone);
        PolicyGradientConfig capped = config(s, false);
        capped.maxTotalSteps = 600;
        Rng again(100 + k);
        expectSameCurves(curves[k], trainPolicyGradient(*environment, *map, capped, again));
        EXPECT_EQ(together[k](), again());
        lengths += curves[k].points.size() != reference.points.size();
      }
      EXPECT_GT(lengths, 0u) << "the step cap never stopped a run early";
    }
  }
}

// A map whose features turn to NaN once the pole leans far: some episodes of an update fail in
// the middle while others go on; both ways count the same steps and stop at the same episode.
class FragileFeatures final : public features::FeatureMap {
 public:
  std::size_t inputDim() const override { return 4; }
  std::size_t outputDim() const override { return 4; }
  void evaluate(const double* state, double* features) const override {
    for (int i = 0; i < 4; ++i) features[i] = state[i];
    if (std::fabs(state[2]) > 0.15) features[1] = std::numeric_limits<double>::quiet_NaN();
  }
};

TEST(Lockstep, ADivergingRunStopsAtTheSameEpisodeAndStep) {
  const auto environment = env::Registry::global().make("cartpole", {{"max_steps", "500"}});
  const FragileFeatures map;
  PolicyGradientConfig c;
  c.updates = 20;
  Rng a(3), b(3);
  c.lockstep = true;
  const LearningCurve lockstep = trainPolicyGradient(*environment, map, c, a);
  c.lockstep = false;
  const LearningCurve sequential = trainPolicyGradient(*environment, map, c, b);
  EXPECT_TRUE(sequential.diverged);
  expectSameCurves(lockstep, sequential);
  // Together with other runs, each stopping where it diverges.
  std::vector<Rng> rngs{Rng(3), Rng(4), Rng(5)};
  c.lockstep = true;
  const std::vector<LearningCurve> runs = trainPolicyGradientRuns(*environment, map, c, rngs);
  expectSameCurves(runs[0], sequential);
  for (std::uint64_t k = 1; k < 3; ++k) {
    Rng alone(3 + k);
    c.lockstep = false;
    expectSameCurves(runs[k], trainPolicyGradient(*environment, map, c, alone));
  }
}

// Without a batched form, lockstep steps copies of the environment (one per lane): the copies are
// made, and the curves are the sequential ones (the tests above).
TEST(Lockstep, WithoutABatchedFormTheLanesStepCopies) {
  registerCountedCartPole();
  const auto environment = env::Registry::global().make("counted-cartpole", {});
  ASSERT_FALSE(env::hasBatchEnvironment(*environment));
  const features::RawFeatureMap map(4);
  PolicyGradientConfig c;
  c.updates = 2;
  c.lockstep = false;
  int before = UnbatchedCartPole::made;
  Rng a(1);
  trainPolicyGradient(*environment, map, c, a);
  EXPECT_EQ(UnbatchedCartPole::made, before);
  c.lockstep = true;
  before = UnbatchedCartPole::made;
  Rng b(1);
  trainPolicyGradient(*environment, map, c, b);
  EXPECT_EQ(UnbatchedCartPole::made - before, 1 + c.episodesPerUpdate);  // Prototype and lanes.
}

// GP fitness goes through the same learner: equal trial fitness both ways.
TEST(Lockstep, TrialFitnessIsTheSameBothWays) {
  run::ExperimentConfig experiment;
  experiment.env = "acrobot";
  experiment.envParams = {{"max_steps", "150"}};
  experiment.learner = "pg";
  experiment.trials = 2;
  experiment.learnerParams = {{"updates", "4"}, {"std", "1.0"}};
  const auto genome = expr::parseFeaturesFile("sin(th1)\ndth2 + dth1\n", "test",
                                              {"th1", "th2", "dth1", "dth2"}, "acrobot")
                          .genome;
  const run::LearningTask lockstep(experiment, run::LearningTask::Budget::Trial);
  experiment.learnerParams["lockstep"] = "false";
  const run::LearningTask sequential(experiment, run::LearningTask::Budget::Trial);
  Rng a(21), b(21);
  const double x = run::trialFitness(lockstep, genome, a);
  const double y = run::trialFitness(sequential, genome, b);
  EXPECT_TRUE(std::isfinite(x));
  EXPECT_TRUE(sameBits(x, y)) << x << " vs " << y;
}

// The trials of a fitness evaluation on an environment without a batched form are played
// together lane by lane (Learner::trainRuns of pg), with the fitness of one after another.
run::ExperimentConfig trialExperiment(const std::string& env) {
  registerCountedCartPole();
  run::ExperimentConfig experiment;
  experiment.env = env;
  experiment.envParams = {{"max_steps", "150"}};
  experiment.learner = "pg";
  experiment.trials = 3;
  experiment.learnerParams = {{"updates", "4"}};
  return experiment;
}

TEST(Lockstep, TrialFitnessWithoutABatchedFormIsTheSameBothWays) {
  run::ExperimentConfig experiment = trialExperiment("counted-cartpole");
  const auto genome = expr::parseFeaturesFile("sin(th)\ndth + dx\n", "test",
                                              {"x", "dx", "th", "dth"}, "counted-cartpole")
                          .genome;
  const run::LearningTask lockstep(experiment, run::LearningTask::Budget::Trial);
  experiment.learnerParams["lockstep"] = "false";
  const run::LearningTask sequential(experiment, run::LearningTask::Budget::Trial);
  Rng a(21), b(21);
  int before = UnbatchedCartPole::made;
  const double x = run::trialFitness(lockstep, genome, a);
  // One environment made for the call, the batch's prototype and one copy per lane (3 trials x
  // 10 episodes); nothing made only to learn whether it can be copied.
  EXPECT_EQ(UnbatchedCartPole::made - before, 2 + 3 * 10);
  before = UnbatchedCartPole::made;
  const double y = run::trialFitness(sequential, genome, b);
  EXPECT_EQ(UnbatchedCartPole::made - before, 3);  // One per trial.
  EXPECT_TRUE(std::isfinite(x));
  EXPECT_TRUE(sameBits(x, y)) << x << " vs " << y;
}

// An environment that cannot be copied, with lockstep asked for: the runs are played one after
// another on the call's one environment, with the same fitness as without lockstep.
TEST(Lockstep, TrialFitnessOfAnEnvironmentThatCannotBeCopiedIsTheSameBothWays) {
  run::ExperimentConfig experiment = trialExperiment("uncopyable-cartpole");
  const auto genome = expr::parseFeaturesFile("sin(th)\ndth + dx\n", "test",
                                              {"x", "dx", "th", "dth"}, "uncopyable-cartpole")
                          .genome;
  const run::LearningTask lockstep(experiment, run::LearningTask::Budget::Trial);
  experiment.learnerParams["lockstep"] = "false";
  const run::LearningTask sequential(experiment, run::LearningTask::Budget::Trial);
  Rng a(21), b(21);
  int before = UnbatchedCartPole::made;
  const double x = run::trialFitness(lockstep, genome, a);
  EXPECT_EQ(UnbatchedCartPole::made - before, 1);  // The call's, shared by the trials.
  const double y = run::trialFitness(sequential, genome, b);
  EXPECT_TRUE(std::isfinite(x));
  EXPECT_TRUE(sameBits(x, y)) << x << " vs " << y;
}

}  // namespace
}  // namespace gpfd::rl
