// Augmented Random Search (rl/ars.hpp): the step against a hand computation, learning on
// cart-pole with discrete actions, determinism for a seed, the lockstep and sequential players and
// runs trained together giving the same bits, V2's statistics, divergence, and bad parameters
// refused by name.
#include "gpfd/rl/ars.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gpfd/env/environment.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/util/error.hpp"
#include "same_curves.hpp"
#include "test_envs.hpp"

namespace gpfd::rl {
namespace {

using testing::expectSameCurves;

std::unique_ptr<env::Environment> discreteCartPole() {
  return env::Registry::global().make("cartpole", {{"actions", "discrete"}, {"max_steps", "500"}});
}

// Where the registry's learner refuses `params`: "accepted" when it does not.
std::string refusalPlace(const Params& params) {
  try {
    LearnerRegistry::global().make("ars", params);
  } catch (const InputError& e) {
    return e.where();
  }
  return "accepted";
}

TEST(Ars, StepIsTheTopDirectionsFiniteDifferenceOverTheirReturnsStd) {
  const std::vector<double> plus{1.0, 5.0, 2.0}, minus{0.0, 3.0, 4.0};
  const std::vector<Eigen::VectorXd> deltas{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                            Eigen::Vector3d(0, 0, 1)};
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(3);
  // b = 2 keeps directions 1 (best 5) and 2 (best 4); their returns 5, 3, 2, 4 have mean 3.5 and
  // population std sqrt(1.25); step 0.1 / (2 sqrt(1.25)) * (2 delta_1 - 2 delta_2).
  arsStep(plus, minus, deltas, 2, 0.1, theta);
  const double c = 0.1 / (2.0 * std::sqrt(1.25));
  EXPECT_DOUBLE_EQ(theta[0], 0.0);
  EXPECT_DOUBLE_EQ(theta[1], 2.0 * c);
  EXPECT_DOUBLE_EQ(theta[2], -2.0 * c);
  // All N directions: the 6 returns' std, 3 differences.
  theta.setZero();
  arsStep(plus, minus, deltas, 3, 0.1, theta);
  const double mean = 15.0 / 6.0;
  double squares = 0.0;
  for (const double r : {1.0, 5.0, 2.0, 0.0, 3.0, 4.0}) squares += (r - mean) * (r - mean);
  const double all = 0.1 / (3.0 * std::sqrt(squares / 6.0));
  EXPECT_DOUBLE_EQ(theta[0], all * 1.0);
  EXPECT_DOUBLE_EQ(theta[1], all * 2.0);
  EXPECT_DOUBLE_EQ(theta[2], all * -2.0);
  // Equal returns: no step (sigma_R = 0).
  theta.setZero();
  const std::vector<double> same{2.0, 2.0, 2.0};
  arsStep(same, same, deltas, 3, 0.1, theta);
  EXPECT_TRUE(theta.isZero(0.0));
}

TEST(Ars, LearnsDiscreteCartPoleFromTheRawVariables) {
  const auto env = discreteCartPole();
  const features::RawFeatureMap raw(4);
  ArsConfig config;
  config.updates = 20;
  Rng rng(1);
  const LearningCurve curve = trainArs(*env, raw, config, rng);
  ASSERT_FALSE(curve.diverged) << curve.divergedReason;
  ASSERT_EQ(curve.points.size(), 21u);
  EXPECT_EQ(curve.episodes, 21 * 16);
  const double start = curve.points.front().meanReturn;
  double last5 = 0.0;
  for (std::size_t u = 16; u <= 20; ++u) last5 += curve.points[u].meanReturn / 5.0;
  EXPECT_LT(start, 50.0);
  EXPECT_GT(last5, start + 100.0) << "start " << start;
  // The learned weights, played unperturbed through the registry's learner.
  const auto learner = LearnerRegistry::global().make("ars", {{"updates", "20"}});
  Rng evalRng(5);
  const Evaluation e = learner->evaluate(*env, raw, curve.weights, 10, evalRng);
  EXPECT_EQ(e.episodes, 10);
  EXPECT_GT(e.meanReturn, start + 100.0);
}

TEST(Ars, SameSeedSameCurveOtherSeedAnother) {
  const auto env = discreteCartPole();
  const features::RawFeatureMap raw(4);
  ArsConfig config;
  config.updates = 5;
  Rng a(3), b(3), c(4);
  const auto first = trainArs(*env, raw, config, a);
  expectSameCurves(first, trainArs(*env, raw, config, b));
  EXPECT_EQ(a(), b());  // Both engines are left alike.
  EXPECT_NE(first.weights.values, trainArs(*env, raw, config, c).weights.values);
}

// Lockstep and sequential players, and runs trained together or one by one, on discrete and
// continuous cart-pole, V1 and V2, b < N, a random start and an unperturbed last row.
TEST(Ars, LockstepSequentialAndRunsTogetherGiveTheSameBits) {
  const features::RawFeatureMap raw(4);
  const std::vector<Params> envs{{{"actions", "discrete"}, {"max_steps", "300"}},
                                 {{"max_steps", "300"}}};
  for (const auto& envParams : envs) {
    for (const bool normalise : {false, true}) {
      ArsConfig config;
      config.updates = 6;
      config.directions = 5;
      config.topDirections = 3;
      config.features.normalise = normalise;
      config.zeroPolicy = normalise;
      config.greedyLastRow = !normalise;
      ArsConfig sequential = config;
      sequential.lockstep = false;
      auto env = env::Registry::global().make("cartpole", envParams);
      std::vector<Rng> together{Rng(1), Rng(2), Rng(3)};
      const auto curves = trainArsRuns(*env, raw, config, together);
      for (std::size_t k = 0; k < together.size(); ++k) {
        SCOPED_TRACE(::testing::Message() << "normalise " << normalise << " run " << k);
        Rng alone(k + 1);
        expectSameCurves(curves[k], trainArs(*env, raw, sequential, alone));
        EXPECT_EQ(alone(), together[k]());
        EXPECT_EQ(curves[k].weights.shift.size(), normalise ? 4u : 0u);
      }
    }
  }
}

TEST(Ars, RegistryTrainRunsEqualsTrainingEachRunAlone) {
  const auto learner = LearnerRegistry::global().make("ars", {{"updates", "3"}, {"n_delta", "4"}});
  const features::RawFeatureMap raw(4);
  std::vector<Rng> rngs{Rng(7), Rng(8)};
  std::vector<std::size_t> rows(2, 0);
  const auto curves = learner->trainRuns(discreteCartPole, raw, rngs,
                                         [&](std::size_t run, const CurvePoint&) { ++rows[run]; });
  EXPECT_EQ(rows, (std::vector<std::size_t>{4, 4}));
  for (std::size_t k = 0; k < 2; ++k) {
    Rng alone(7 + k);
    expectSameCurves(curves[k], learner->train(*discreteCartPole(), raw, alone));
  }
}

// V2 on the bandit, whose states are U(-1, 1): the statistics exported are theirs.
TEST(Ars, V2NormalisesByTheMeanAndStdOfTheStatesSeen) {
  testing::LinearBandit env;
  const features::RawFeatureMap raw(1);
  ArsConfig config;
  config.updates = 60;
  config.features.normalise = true;
  Rng rng(2);
  const auto curve = trainArs(env, raw, config, rng);
  ASSERT_FALSE(curve.diverged);
  ASSERT_EQ(curve.weights.shift.size(), 1u);
  EXPECT_NEAR(curve.weights.shift[0], 0.0, 0.06);
  EXPECT_NEAR(curve.weights.scale[0], 1.0 / std::sqrt(3.0), 0.04);
  // V1 exports none.
  config.features.normalise = false;
  Rng again(2);
  EXPECT_TRUE(trainArs(env, raw, config, again).weights.shift.empty());
}

TEST(Ars, ANonFiniteStateMarksTheCurveDivergedWithoutThrowing) {
  testing::PoisonedEnv env;
  const features::RawFeatureMap raw(1);
  for (const bool lockstep : {true, false}) {
    ArsConfig config;
    config.lockstep = lockstep;
    Rng rng(1);
    const auto curve = trainArs(env, raw, config, rng);
    EXPECT_TRUE(curve.diverged);
    EXPECT_TRUE(curve.points.empty());
    EXPECT_EQ(curve.episodes, 1);  // The episodes after the first that failed are not counted.
  }
}

TEST(Ars, RefusesBadParametersByName) {
  EXPECT_EQ(refusalPlace({{"n_delta", "4"}, {"n_top", "5"}}), "ars.n_top");
  EXPECT_EQ(refusalPlace({{"n_top", "9"}}), "ars.n_top");  // n_delta's default is 8.
  EXPECT_EQ(refusalPlace({{"delta_std", "-0.05"}}), "ars.delta_std");
  EXPECT_EQ(refusalPlace({{"delta_std", "0"}}), "ars.delta_std");
  EXPECT_EQ(refusalPlace({{"learning_rate", "-1"}}), "ars.learning_rate");
  EXPECT_EQ(refusalPlace({{"n_delta", "0"}}), "ars.n_delta");
  EXPECT_EQ(refusalPlace({{"step", "natural"}}), "ars.step");
  EXPECT_EQ(refusalPlace({{"n_delta", "4"}, {"n_top", "4"}}), "accepted");
  try {
    LearnerRegistry::global().make("ars", {{"n_delta", "4"}, {"n_top", "5"}});
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("n_top"), std::string::npos) << e.what();
  }
  // The algorithm itself checks what the table does.
  const auto env = discreteCartPole();
  const features::RawFeatureMap raw(4);
  ArsConfig config;
  config.topDirections = 9;
  Rng rng(1);
  EXPECT_THROW(trainArs(*env, raw, config, rng), InputError);
}

// zero_policy = false: weights uniform in +-1/sqrt(4) over cart-pole's raw variables (the bias's
// too); true: zeros.
TEST(Ars, StartsFromZeroOrFromUniformWeightsWithinTheFanInBound) {
  const auto env = discreteCartPole();
  const features::RawFeatureMap raw(4);
  ArsConfig config;
  config.updates = 0;
  Rng a(1), b(1);
  const auto zero = trainArs(*env, raw, config, a);
  ASSERT_EQ(zero.weights.values.size(), 10u);  // 2 choices x (4 + bias).
  for (const double w : zero.weights.values) EXPECT_EQ(w, 0.0);
  config.zeroPolicy = false;
  const auto random = trainArs(*env, raw, config, b);
  double spread = 0.0;
  for (const double w : random.weights.values) {
    EXPECT_LE(std::abs(w), 0.5);
    spread += std::abs(w);
  }
  EXPECT_GT(spread, 0.5);
}

TEST(Ars, IsRegisteredWithItsBudgetAndNeeds) {
  const auto& info = LearnerRegistry::global().info("ars");
  EXPECT_EQ(info.budgetParam, "updates");
  auto tetris = env::Registry::global().make("tetris");
  EXPECT_THROW(LearnerRegistry::global().checkSuitable("ars", *tetris), InputError);
  EXPECT_NO_THROW(LearnerRegistry::global().checkSuitable("ars", *discreteCartPole()));
  const auto defaults = arsParams().write(ArsConfig{});
  EXPECT_EQ(defaults.at("n_delta"), "8");
  EXPECT_EQ(defaults.at("learning_rate"), "0.02");
  EXPECT_EQ(defaults.at("delta_std"), "0.05");
  EXPECT_EQ(defaults.at("zero_policy"), "true");
}

}  // namespace
}  // namespace gpfd::rl
