#include "gpfd/rl/policy_gradient.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/gradient_estimator.hpp"
#include "gpfd/rl/linear_policy.hpp"
#include "gpfd/util/error.hpp"
#include "test_envs.hpp"

namespace gpfd::rl {
namespace {

using testing::Corridor;
using testing::LinearBandit;
using testing::PoisonedEnv;

// Monte-Carlo expected return of the bandit for a ~ N(w0 s + w1, sd^2) with common random numbers
// (the same seed for every call), so that finite differences of it are smooth.
double simulatedReturn(const LinearBandit& bandit, double w0, double w1, double sd, int n) {
  Rng rng(99);
  LinearBandit env = bandit;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    env.reset(rng);
    const double s = env.state()[0];
    const double a = w0 * s + w1 + sd * rng.normal();
    sum += env.step(std::span<const double>(&a, 1)).reward;
  }
  return sum / n;
}

TEST(PolicyGradient, EstimateMatchesFiniteDifferences) {
  const LinearBandit bandit(1.0, 0.0);
  LinearBandit env = bandit;
  const features::RawFeatureMap raw(1);
  PolicyGradientConfig config;
  config.policy.initialStd = 0.5;
  config.policy.learnStd = true;
  const double w0 = 0.2, w1 = 0.3, logSd = std::log(0.5);
  Eigen::VectorXd params(3);
  params << w0, w1, logSd;
  Rng rng(7);
  const Eigen::VectorXd g = estimatePolicyGradient(env, raw, config, params, 400000, rng);
  ASSERT_EQ(g.size(), 3);

  const int n = 200000;
  const double h = 1e-4;
  const double fd0 =
      (simulatedReturn(bandit, w0 + h, w1, 0.5, n) - simulatedReturn(bandit, w0 - h, w1, 0.5, n)) /
      (2 * h);
  const double fd1 =
      (simulatedReturn(bandit, w0, w1 + h, 0.5, n) - simulatedReturn(bandit, w0, w1 - h, 0.5, n)) /
      (2 * h);
  const double fdSd = (simulatedReturn(bandit, w0, w1, std::exp(logSd + h), n) -
                       simulatedReturn(bandit, w0, w1, std::exp(logSd - h), n)) /
                      (2 * h);
  // Exact values: -2 (w0 - 1) / 3 = 0.5333, -2 w1 = -0.6, -2 sd^2 = -0.5.
  EXPECT_NEAR(fd0, 0.5333, 0.02);
  EXPECT_NEAR(fd1, -0.6, 0.02);
  EXPECT_NEAR(fdSd, -0.5, 0.02);
  EXPECT_NEAR(g[0], fd0, 0.03);
  EXPECT_NEAR(g[1], fd1, 0.03);
  EXPECT_NEAR(g[2], fdSd, 0.03);
}

TEST(PolicyGradient, SoftmaxLogLikelihoodGradientMatchesFiniteDifferences) {
  env::ActionSpace space;
  space.kind = env::ActionSpace::Kind::Discrete;
  space.choices = {3};
  LinearPolicy policy(space, 2, {});
  policy.parameters() << 0.3, -0.2, 0.1, 0.5, -0.4, 0.2;
  const double phi[2] = {0.7, -1.3};
  auto logProb = [&](const Eigen::VectorXd& p, int a) {
    double z[3], top = -1e300, total = 0.0;
    for (int k = 0; k < 3; ++k)
      top = std::max(top, z[k] = p[2 * k] * phi[0] + p[2 * k + 1] * phi[1]);
    for (double v : z) total += std::exp(v - top);
    return z[a] - top - std::log(total);
  };
  Rng rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    double action = -1.0;
    Eigen::VectorXd grad = Eigen::VectorXd::Zero(6);
    ASSERT_TRUE(policy.sample(rng, phi, &action, grad.data()));
    const int a = static_cast<int>(action);
    ASSERT_GE(a, 0);
    ASSERT_LT(a, 3);
    for (int k = 0; k < 6; ++k) {
      Eigen::VectorXd up = policy.parameters(), down = policy.parameters();
      up[k] += 1e-6;
      down[k] -= 1e-6;
      EXPECT_NEAR(grad[k], (logProb(up, a) - logProb(down, a)) / 2e-6, 1e-6);
    }
  }
}

// Sum over parameters of the variance of the gradient estimate over many batches.
double estimateVariance(bool baseline) {
  LinearBandit env(1.0, 10.0);  // A large reward offset: the case a baseline is for.
  const features::RawFeatureMap raw(1);
  PolicyGradientConfig config;
  config.optimalBaseline = baseline;
  Eigen::VectorXd params(2);
  params << 0.2, 0.3;
  Rng rng(11);
  const int batches = 400;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(2), sumSq = Eigen::VectorXd::Zero(2);
  for (int b = 0; b < batches; ++b) {
    const Eigen::VectorXd g = estimatePolicyGradient(env, raw, config, params, 10, rng);
    sum += g;
    sumSq += g.cwiseAbs2();
  }
  return ((sumSq - sum.cwiseAbs2() / batches) / (batches - 1)).sum();
}

TEST(PolicyGradient, OptimalBaselineReducesVariance) {
  const double with = estimateVariance(true);
  const double without = estimateVariance(false);
  EXPECT_LT(with, 0.1 * without) << "with " << with << " without " << without;
}

TEST(GradientEstimator, BaselineIsTheWeightedMeanReturn) {
  EpisodicGradientEstimator estimator(1, true);
  estimator.addEpisode(Eigen::VectorXd::Constant(1, 1.0), 2.0);
  estimator.addEpisode(Eigen::VectorXd::Constant(1, -2.0), 5.0);
  Eigen::VectorXd b, g;
  estimator.baseline(b);
  // b = (1 * 2 + 4 * 5) / (1 + 4) = 4.4; g = (1 (2 - 4.4) - 2 (5 - 4.4)) / 2 = -1.8.
  EXPECT_NEAR(b[0], 4.4, 1e-12);
  estimator.gradient(g);
  EXPECT_NEAR(g[0], -1.8, 1e-12);
}

// Equal returns carry no information: the estimate is exactly zero, not rounding noise (on whose
// sign Rprop would still step).
TEST(GradientEstimator, EqualReturnsGiveAnExactlyZeroGradient) {
  EpisodicGradientEstimator estimator(3, true);
  Rng rng(5);
  for (int e = 0; e < 10; ++e) {
    Eigen::VectorXd eligibility(3);
    for (int k = 0; k < 3; ++k) eligibility[k] = rng.normal();
    estimator.addEpisode(eligibility, -500.0);
  }
  Eigen::VectorXd g, b;
  estimator.gradient(g);
  estimator.baseline(b);
  EXPECT_EQ(g, Eigen::VectorXd::Zero(3));
  EXPECT_EQ(b, Eigen::VectorXd::Constant(3, -500.0));
}

TEST(PolicyGradient, LearnsTheBandit) {
  LinearBandit env(0.8, 0.0);
  const features::RawFeatureMap raw(1);
  PolicyGradientConfig config;
  config.updates = 150;
  config.policy.initialStd = 0.3;
  Rng rng(5);
  const LearningCurve curve = trainPolicyGradient(env, raw, config, rng);
  ASSERT_FALSE(curve.diverged);
  ASSERT_EQ(curve.points.size(), 151u);
  EXPECT_EQ(curve.points.back().episodes, 1510);
  ASSERT_EQ(curve.weights.values.size(), 2u);  // Slope and bias.
  EXPECT_NEAR(curve.weights.values[0], 0.8, 0.15);
  EXPECT_NEAR(curve.weights.values[1], 0.0, 0.1);
}

TEST(PolicyGradient, SoftmaxLearnsTheCorridorAndEvaluatesGreedily) {
  Corridor env(4, 40);
  const features::RawFeatureMap raw(1);
  PolicyGradientConfig config;
  config.updates = 60;
  Rng rng(2);
  const LearningCurve curve = trainPolicyGradient(env, raw, config, rng);
  ASSERT_FALSE(curve.diverged);
  EXPECT_LT(curve.points.front().meanReturn, -10.0);
  EXPECT_GT(curve.finalMeanReturn(), -6.0);
  const EvaluationResult greedy = evaluatePolicy(env, raw, curve.weights, config, 5, true, rng);
  EXPECT_EQ(greedy.episodes, 5);
  EXPECT_DOUBLE_EQ(greedy.meanReturn, -3.0);  // Four steps right, the last one terminal (0).
}

// greedy_last changes the last row only: it is the final weights played without exploration,
// which on the corridor (a fixed start) is the greedy evaluation's return exactly.
TEST(PolicyGradient, GreedyLastRowPlaysTheFinalWeightsWithoutExploration) {
  Corridor env(4, 40);
  const features::RawFeatureMap raw(1);
  PolicyGradientConfig sampled;
  sampled.updates = 10;  // Still exploring: the sampled last row is not the greedy one.
  PolicyGradientConfig greedy = sampled;
  greedy.greedyLastRow = true;
  Rng a(2), b(2);
  const LearningCurve x = trainPolicyGradient(env, raw, sampled, a);
  const LearningCurve y = trainPolicyGradient(env, raw, greedy, b);
  ASSERT_FALSE(y.diverged);
  ASSERT_EQ(x.points.size(), y.points.size());
  for (std::size_t i = 0; i + 1 < x.points.size(); ++i) {
    EXPECT_EQ(x.points[i].meanReturn, y.points[i].meanReturn) << i;
    EXPECT_EQ(x.points[i].steps, y.points[i].steps) << i;
  }
  EXPECT_EQ(x.weights.values, y.weights.values);
  EXPECT_NE(x.finalMeanReturn(), y.finalMeanReturn());
  Rng c(3);
  EXPECT_EQ(y.finalMeanReturn(),
            evaluatePolicy(env, raw, y.weights, sampled, 5, true, c).meanReturn);
}

TEST(PolicyGradient, SameSeedSameCurve) {
  LinearBandit env(1.0, 0.0);
  const features::RawFeatureMap raw(1);
  PolicyGradientConfig config;
  config.updates = 20;
  config.features.normalise = true;
  Rng a(42), b(42);
  const LearningCurve x = trainPolicyGradient(env, raw, config, a);
  const LearningCurve y = trainPolicyGradient(env, raw, config, b);
  ASSERT_EQ(x.points.size(), y.points.size());
  for (std::size_t i = 0; i < x.points.size(); ++i) {
    EXPECT_EQ(x.points[i].meanReturn, y.points[i].meanReturn);
  }
  EXPECT_EQ(x.weights.values, y.weights.values);
}

TEST(PolicyGradient, NonFiniteStateMarksTheRunDiverged) {
  PoisonedEnv env;
  const features::RawFeatureMap raw(1);
  PolicyGradientConfig config;
  config.updates = 5;
  Rng rng(1);
  const LearningCurve curve = trainPolicyGradient(env, raw, config, rng);
  EXPECT_TRUE(curve.diverged);
  EXPECT_TRUE(curve.points.empty());
  EXPECT_FALSE(curve.divergedReason.empty());
}

TEST(PolicyGradient, WrongFeatureInputIsAnInputError) {
  LinearBandit env;
  const features::RawFeatureMap raw(3);
  Rng rng(1);
  EXPECT_THROW(trainPolicyGradient(env, raw, {}, rng), InputError);
}

}  // namespace
}  // namespace gpfd::rl
