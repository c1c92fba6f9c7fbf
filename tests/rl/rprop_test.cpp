#include "gpfd/rl/rprop.hpp"

#include <gtest/gtest.h>

namespace gpfd::rl {
namespace {

TEST(Rprop, PaperPresets) {
  const auto large = RpropConfig::paperLarge();
  EXPECT_EQ(large.deltaMin, 0.01);
  EXPECT_EQ(large.deltaInitial, 0.1);
  EXPECT_EQ(large.deltaMax, 0.5);
  const auto small = RpropConfig::paperSmall();
  EXPECT_EQ(small.deltaMin, 0.002);
  EXPECT_EQ(small.deltaInitial, 0.02);
  EXPECT_EQ(small.deltaMax, 0.1);
}

TEST(Rprop, FirstStepMovesByInitialDeltaAlongTheSign) {
  Rprop rprop(RpropConfig::paperLarge(), 3);
  Eigen::VectorXd params = Eigen::VectorXd::Zero(3);
  rprop.step(Eigen::Vector3d(5.0, -1e-9, 0.0), params);
  EXPECT_DOUBLE_EQ(params[0], 0.1);
  EXPECT_DOUBLE_EQ(params[1], -0.1);
  EXPECT_DOUBLE_EQ(params[2], 0.0);  // A zero gradient does not move.
}

TEST(Rprop, SameSignGrowsUpToMax) {
  Rprop rprop(RpropConfig::paperLarge(), 1);
  Eigen::VectorXd params = Eigen::VectorXd::Zero(1);
  const Eigen::VectorXd g = Eigen::VectorXd::Constant(1, 2.0);
  rprop.step(g, params);  // delta 0.1 (first step: no previous gradient).
  rprop.step(g, params);  // 0.12
  EXPECT_NEAR(rprop.deltas()[0], 0.12, 1e-15);
  EXPECT_NEAR(params[0], 0.22, 1e-15);
  for (int i = 0; i < 20; ++i) rprop.step(g, params);
  EXPECT_DOUBLE_EQ(rprop.deltas()[0], 0.5);
}

TEST(Rprop, SignFlipShrinksAndSkipsThenMovesWithoutGrowing) {
  Rprop rprop(RpropConfig::paperLarge(), 1);
  Eigen::VectorXd params = Eigen::VectorXd::Zero(1);
  rprop.step(Eigen::VectorXd::Constant(1, 1.0), params);   // +0.1
  rprop.step(Eigen::VectorXd::Constant(1, 1.0), params);   // +0.12
  rprop.step(Eigen::VectorXd::Constant(1, -1.0), params);  // flip: delta 0.06, no move.
  EXPECT_NEAR(rprop.deltas()[0], 0.06, 1e-15);
  EXPECT_NEAR(params[0], 0.22, 1e-15);
  // iRprop-: the stored gradient is 0, so the next step neither grows nor shrinks delta.
  rprop.step(Eigen::VectorXd::Constant(1, -1.0), params);
  EXPECT_NEAR(rprop.deltas()[0], 0.06, 1e-15);
  EXPECT_NEAR(params[0], 0.16, 1e-15);
}

TEST(Rprop, ShrinkingStopsAtMin) {
  Rprop rprop(RpropConfig::paperSmall(), 1);
  Eigen::VectorXd params = Eigen::VectorXd::Zero(1);
  double sign = 1.0;
  for (int i = 0; i < 40; ++i) {
    rprop.step(Eigen::VectorXd::Constant(1, sign), params);
    rprop.step(Eigen::VectorXd::Constant(1, sign), params);
    sign = -sign;
  }
  EXPECT_GE(rprop.deltas()[0], 0.002);
  EXPECT_LT(rprop.deltas()[0], 0.0025);
}

}  // namespace
}  // namespace gpfd::rl
