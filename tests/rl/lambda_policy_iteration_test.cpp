#include "gpfd/rl/lambda_policy_iteration.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <limits>

#include "gpfd/features/feature_map.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::rl {
namespace {

TEST(LambdaReturns, HandComputedTerminalGame) {
  // J = (1, 2, 3), rewards between afterstates (0.5, 1), final move's reward 2, game over:
  // d = (0.5 + 2 - 1, 1 + 3 - 2, 2 + 0 - 3) = (1.5, 2, -1); with lambda 0.5:
  // D2 = -1, D1 = 2 - 0.5 = 1.5, D0 = 1.5 + 0.75 = 2.25; targets = J + D.
  const double values[3] = {1.0, 2.0, 3.0};
  const double rewards[3] = {0.5, 1.0, 2.0};
  double targets[3];
  lambdaReturns(values, rewards, true, 0.5, targets);
  EXPECT_DOUBLE_EQ(targets[0], 3.25);
  EXPECT_DOUBLE_EQ(targets[1], 3.5);
  EXPECT_DOUBLE_EQ(targets[2], 2.0);
}

TEST(LambdaReturns, CappedGameBootstrapsTheLastAfterstate) {
  // Not terminal: d2 = 0, D1 = 2, D0 = 1.5 + 0.5 * 2 = 2.5.
  const double values[3] = {1.0, 2.0, 3.0};
  const double rewards[3] = {0.5, 1.0, 99.0};  // The last reward is unknown and ignored.
  double targets[3];
  lambdaReturns(values, rewards, false, 0.5, targets);
  EXPECT_DOUBLE_EQ(targets[0], 3.5);
  EXPECT_DOUBLE_EQ(targets[1], 4.0);
  EXPECT_DOUBLE_EQ(targets[2], 3.0);
}

TEST(LambdaReturns, LambdaOneIsTheMonteCarloReturnAndZeroTheOneStepTarget) {
  const double values[4] = {0.3, -1.0, 2.5, 0.7};
  const double rewards[4] = {1.0, 0.0, 2.0, 3.0};
  double mc[4], td[4];
  lambdaReturns(values, rewards, true, 1.0, mc);
  lambdaReturns(values, rewards, true, 0.0, td);
  EXPECT_DOUBLE_EQ(mc[0], 6.0);
  EXPECT_DOUBLE_EQ(mc[1], 5.0);
  EXPECT_DOUBLE_EQ(mc[2], 5.0);
  EXPECT_DOUBLE_EQ(mc[3], 3.0);
  EXPECT_DOUBLE_EQ(td[0], 1.0 - 1.0);
  EXPECT_DOUBLE_EQ(td[1], 0.0 + 2.5);
  EXPECT_DOUBLE_EQ(td[2], 2.0 + 0.7);
  EXPECT_DOUBLE_EQ(td[3], 3.0);
}

TEST(LeastSquares, MatchesADirectSolve) {
  const Eigen::Index n = 200, d = 5;
  Rng rng(8);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> phi(n, d);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < d; ++j) phi(i, j) = rng.normal() * static_cast<double>(j + 1);
    y[i] = rng.normal(3.0, 2.0);
  }
  const double ridge = 0.01;
  LeastSquaresAccumulator acc(d);
  acc.add(phi.data(), y.data(), 120);  // In two blocks.
  acc.add(phi.data() + 120 * d, y.data() + 120, n - 120);
  Eigen::VectorXd r;
  ASSERT_TRUE(acc.solve(ridge, r));
  // Direct: the stacked system [phi; sqrt(n ridge) I] r = [y; 0] by QR.
  Eigen::MatrixXd stacked(n + d, d);
  stacked.topRows(n) = phi;
  stacked.bottomRows(d) =
      std::sqrt(static_cast<double>(n) * ridge) * Eigen::MatrixXd::Identity(d, d);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + d);
  rhs.head(n) = y;
  const Eigen::VectorXd direct = stacked.colPivHouseholderQr().solve(rhs);
  for (Eigen::Index j = 0; j < d; ++j) EXPECT_NEAR(r[j], direct[j], 1e-10);
}

// A game without choices: the height goes up by 1 per move with reward 1; the move into height
// `top` ends the game. The value of afterstate h is top - h, exactly linear in (h, 1).
class Climb final : public AfterstateProblem {
 public:
  explicit Climb(int top, double poisonAt = -1) : top_(top), poisonAt_(poisonAt) {}
  std::size_t stateDim() const override { return 1; }
  void reset(Rng&) override { h_ = 0; }
  AfterstateView candidates() override {
    next_ = h_ + 1.0;
    if (next_ == poisonAt_) next_ = std::numeric_limits<double>::quiet_NaN();
    end_ = (h_ + 1 >= top_) ? 1 : 0;
    return {1, &next_, &reward_, &end_};
  }
  void choose(std::size_t, Rng&) override { ++h_; }

 private:
  int top_;
  double poisonAt_;
  int h_ = 0;
  double next_ = 0.0, reward_ = 1.0;
  std::uint8_t end_ = 0;
};

TEST(LambdaPolicyIteration, LambdaOneFitsTheExactValueInOneIteration) {
  Climb game(10);
  const features::RawFeatureMap raw(1);
  LambdaPolicyIterationConfig config;
  config.iterations = 1;
  config.gamesPerIteration = 3;
  config.lambda = 1.0;
  config.ridge = 0.0;
  Rng rng(1);
  const LearningCurve curve = trainLambdaPolicyIteration(game, raw, config, rng);
  ASSERT_FALSE(curve.diverged);
  ASSERT_EQ(curve.points.size(), 2u);
  EXPECT_EQ(curve.points[0].meanReturn, 10.0);
  EXPECT_EQ(curve.points[1].episodes, 6);
  EXPECT_EQ(curve.points[1].steps, 60);
  ASSERT_EQ(curve.weights.values.size(), 2u);
  EXPECT_NEAR(curve.weights.values[0], -1.0, 1e-9);
  EXPECT_NEAR(curve.weights.values[1], 10.0, 1e-9);
}

TEST(LambdaPolicyIteration, SmallerLambdaConvergesToTheSameValue) {
  Climb game(10);
  const features::RawFeatureMap raw(1);
  LambdaPolicyIterationConfig config;
  config.iterations = 60;
  config.gamesPerIteration = 1;
  config.lambda = 0.6;
  config.ridge = 0.0;
  Rng rng(1);
  const LearningCurve curve = trainLambdaPolicyIteration(game, raw, config, rng);
  ASSERT_FALSE(curve.diverged);
  EXPECT_NEAR(curve.weights.values[0], -1.0, 1e-6);
  EXPECT_NEAR(curve.weights.values[1], 10.0, 1e-6);
}

TEST(LambdaPolicyIteration, CappedGamesAndGreedyPlay) {
  Climb game(1000);
  const features::RawFeatureMap raw(1);
  LambdaPolicyIterationConfig config;
  config.iterations = 2;
  config.gamesPerIteration = 2;
  config.maxMovesPerGame = 7;
  config.initialWeights = {0.5, 1.0};
  Rng rng(1);
  const LearningCurve curve = trainLambdaPolicyIteration(game, raw, config, rng);
  ASSERT_FALSE(curve.diverged);
  EXPECT_EQ(curve.points.back().steps, 3 * 2 * 7);
  EXPECT_EQ(curve.points.back().meanReturn, 7.0);
  const GreedyPlayResult play = playGreedy(game, raw, curve.weights, config, 3, rng);
  EXPECT_EQ(play.games, 3);
  EXPECT_EQ(play.meanReturn, 7.0);
}

TEST(LambdaPolicyIteration, NonFiniteFeatureMarksTheRunDiverged) {
  Climb game(10, 4.0);
  const features::RawFeatureMap raw(1);
  LambdaPolicyIterationConfig config;
  config.iterations = 3;
  config.gamesPerIteration = 2;
  Rng rng(1);
  const LearningCurve curve = trainLambdaPolicyIteration(game, raw, config, rng);
  EXPECT_TRUE(curve.diverged);
  EXPECT_TRUE(curve.points.empty());
}

TEST(LambdaPolicyIteration, BadInitialWeightsAreAnInputError) {
  Climb game(10);
  const features::RawFeatureMap raw(1);
  LambdaPolicyIterationConfig config;
  config.initialWeights = {1.0, 2.0, 3.0};
  Rng rng(1);
  EXPECT_THROW(trainLambdaPolicyIteration(game, raw, config, rng), InputError);
}

}  // namespace
}  // namespace gpfd::rl
