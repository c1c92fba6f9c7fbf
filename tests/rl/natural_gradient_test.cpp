#include "gpfd/rl/natural_gradient.hpp"

#include <gtest/gtest.h>

#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/policy_gradient.hpp"
#include "same_curves.hpp"
#include "test_envs.hpp"

namespace gpfd::rl {
namespace {

using testing::Corridor;
using testing::expectSameCurves;
using testing::LinearBandit;

// Returns that are exactly linear in the eligibilities give back their coefficients as the
// direction, and the step's size is the one whose quadratic KL, per step, is kl:
// (1/2) d' F d / T = kl with F the mean of e e'.
TEST(NaturalGradientStep, FitsTheReturnsAndSizesTheStepByKl) {
  const Eigen::Vector2d w(0.5, -2.0);
  NaturalGradientStep natural(2);
  Rng rng(3);
  Eigen::Matrix2d fisher = Eigen::Matrix2d::Zero();
  const int episodes = 30;
  for (int i = 0; i < episodes; ++i) {
    const Eigen::Vector2d e(rng.normal(), rng.normal());
    fisher += e * e.transpose() / episodes;
    natural.addEpisode(e, 7.0 + e.dot(w), 20);
  }
  Eigen::VectorXd step;
  natural.step(0.01, step);
  ASSERT_EQ(step.size(), 2);
  const double scale = step[0] / w[0];
  EXPECT_GT(scale, 0.0);
  EXPECT_NEAR(step[1] / w[1], scale, 1e-6 * scale);
  EXPECT_NEAR(0.5 * step.dot(fisher * step) / 20.0, 0.01, 1e-9);
}

TEST(NaturalGradientStep, EqualReturnsOrOneEpisodeGiveNoStep) {
  NaturalGradientStep natural(3);
  Rng rng(5);
  Eigen::VectorXd step;
  for (int e = 0; e < 10; ++e) {
    natural.addEpisode(Eigen::Vector3d(rng.normal(), rng.normal(), rng.normal()), -500.0, 10);
    natural.step(0.01, step);
    EXPECT_EQ(step, Eigen::VectorXd::Zero(3)) << e;
  }
  natural.clear();
  natural.addEpisode(Eigen::Vector3d(1.0, 2.0, 3.0), 4.0, 10);
  natural.step(0.01, step);
  EXPECT_EQ(step, Eigen::VectorXd::Zero(3));
}

// Trains from seed `seed` on the raw state with natural steps of KL 0.05.
LearningCurve trainNatural(env::Environment& env, int updates, int episodes, std::uint64_t seed) {
  PolicyGradientConfig config;
  config.step = StepRule::Natural;
  config.naturalKl = 0.05;
  config.updates = updates;
  config.episodesPerUpdate = episodes;
  config.policy.initialStd = 0.3;
  Rng rng(seed);
  return trainPolicyGradient(env, features::RawFeatureMap(env.stateDim()), config, rng);
}

// Natural steps learn the bandit's slope in a tenth of the updates that Rprop needs
// (PolicyGradient.LearnsTheBandit: 150).
TEST(PolicyGradientNatural, LearnsTheBanditInFewUpdates) {
  LinearBandit env(0.8, 0.0);
  const LearningCurve curve = trainNatural(env, 15, 20, 5);
  ASSERT_FALSE(curve.diverged);
  ASSERT_EQ(curve.weights.values.size(), 2u);
  EXPECT_NEAR(curve.weights.values[0], 0.8, 0.15);
  EXPECT_NEAR(curve.weights.values[1], 0.0, 0.1);
}

// A softmax's parameters are redundant (adding a constant to every choice's weights changes
// nothing), so its Fisher matrix is singular: the ridge keeps the step defined.
TEST(PolicyGradientNatural, SoftmaxLearnsTheCorridor) {
  Corridor env(4, 40);
  const LearningCurve curve = trainNatural(env, 30, 10, 2);
  ASSERT_FALSE(curve.diverged);
  EXPECT_LT(curve.points.front().meanReturn, -10.0);
  EXPECT_GT(curve.finalMeanReturn(), -6.0);
}

TEST(PolicyGradientNatural, LockstepAndSequentialGiveTheSameCurves) {
  LinearBandit env(0.8, 0.2);
  const features::RawFeatureMap raw(1);
  PolicyGradientConfig config;
  config.step = StepRule::Natural;
  config.updates = 12;
  config.policy.learnStd = true;
  PolicyGradientConfig sequential = config;
  sequential.lockstep = false;
  Rng a(9), b(9);
  expectSameCurves(trainPolicyGradient(env, raw, config, a),
                   trainPolicyGradient(env, raw, sequential, b));
}

}  // namespace
}  // namespace gpfd::rl
