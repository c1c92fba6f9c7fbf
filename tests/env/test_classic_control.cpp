// Acrobot and cart-pole: start distributions, rewards, terminal and time-limit rules, action
// handling, parameters and seeding.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "gpfd/env/acrobot.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

std::vector<double> rollout(Environment& e, std::uint64_t seed, int steps) {
  Rng rng(seed);
  e.reset(rng);
  std::vector<double> trace(e.state().begin(), e.state().end());
  std::vector<double> action(e.actionSpace().components);
  for (int t = 0; t < steps; ++t) {
    e.sampleAction(rng, action);
    const StepResult r = e.step(action);
    trace.insert(trace.end(), e.state().begin(), e.state().end());
    trace.push_back(r.reward);
    if (r.terminated) break;
  }
  return trace;
}

TEST(Acrobot, ResetDrawsEachVariableFromPlusMinusPointOne) {
  Acrobot a;
  Rng rng(3);
  for (int i = 0; i < 200; ++i) {
    a.reset(rng);
    for (double v : a.state()) {
      EXPECT_GE(v, -0.1);
      EXPECT_LT(v, 0.1);
    }
  }
}

TEST(Acrobot, SameSeedSameTrajectoryOtherSeedOther) {
  Acrobot a, b;
  EXPECT_EQ(rollout(a, 11, 100), rollout(b, 11, 100));
  EXPECT_NE(rollout(a, 11, 100), rollout(b, 12, 100));
}

TEST(Acrobot, RewardIsMinusOneUntilTheTerminalStep) {
  Acrobot a;
  a.setState(std::vector<double>{0, 0, 0, 0});
  const double tau = 0.0;
  const StepResult r = a.step(std::span<const double>(&tau, 1));
  EXPECT_EQ(r.reward, -1.0);
  EXPECT_FALSE(r.terminated);
  // Hanging straight up: -cos(pi) - cos(pi) = 2 > 1, and a zero-torque step keeps it up there.
  a.setState(std::vector<double>{std::numbers::pi, 0, 0, 0});
  EXPECT_TRUE(a.terminal());
  const StepResult up = a.step(std::span<const double>(&tau, 1));
  EXPECT_TRUE(up.terminated);
  EXPECT_EQ(up.reward, 0.0);
}

TEST(Acrobot, TruncatesAtMaxStepsWithoutTerminating) {
  Acrobot a(AcrobotConfig::fromParams({{"max_steps", "5"}}));
  a.setState(std::vector<double>{0, 0, 0, 0});
  const double tau = 0.0;
  for (int t = 1; t <= 5; ++t) {
    const StepResult r = a.step(std::span<const double>(&tau, 1));
    EXPECT_EQ(r.truncated, t == 5);
    EXPECT_FALSE(r.terminated);
  }
}

TEST(Acrobot, ClipsTorqueAndTakesNanAsZero) {
  Acrobot a, b;
  const std::vector<double> s{0.3, -0.2, 0.5, 0.1};
  a.setState(s);
  b.setState(s);
  const double big = 7.0, one = 1.0;
  a.step(std::span<const double>(&big, 1));
  b.step(std::span<const double>(&one, 1));
  EXPECT_EQ(std::vector<double>(a.state().begin(), a.state().end()),
            std::vector<double>(b.state().begin(), b.state().end()));
  const double nan = std::numeric_limits<double>::quiet_NaN(), zero = 0.0;
  a.setState(s);
  b.setState(s);
  a.step(std::span<const double>(&nan, 1));
  b.step(std::span<const double>(&zero, 1));
  EXPECT_EQ(std::vector<double>(a.state().begin(), a.state().end()),
            std::vector<double>(b.state().begin(), b.state().end()));
}

TEST(Acrobot, DiscreteActionsAreMinusZeroPlusTorque) {
  Acrobot d(AcrobotConfig::fromParams({{"actions", "discrete"}, {"max_torque", "2"}}));
  Acrobot c(AcrobotConfig::fromParams({{"max_torque", "2"}}));
  EXPECT_EQ(d.actionSpace().choices, std::vector<int>{3});
  const std::vector<double> s{0.3, -0.2, 0.5, 0.1};
  for (int i = 0; i < 3; ++i) {
    d.setState(s);
    c.setState(s);
    const double index = i, torque = 2.0 * (i - 1);
    d.step(std::span<const double>(&index, 1));
    c.step(std::span<const double>(&torque, 1));
    EXPECT_EQ(d.state()[3], c.state()[3]);
  }
  const double bad = 3.0;
  EXPECT_THROW(d.step(std::span<const double>(&bad, 1)), InputError);
}

TEST(Acrobot, RejectsBadStatesAndParameters) {
  Acrobot a;
  EXPECT_THROW(a.setState(std::vector<double>{0, 0, 0}), InputError);
  EXPECT_THROW(a.setState(std::vector<double>{0, 0, 0, std::numeric_limits<double>::infinity()}),
               InputError);
  EXPECT_THROW(AcrobotConfig::fromParams({{"dt", "-1"}}), InputError);
  EXPECT_THROW(AcrobotConfig::fromParams({{"dt", "abc"}}), InputError);
  EXPECT_THROW(AcrobotConfig::fromParams({{"integrator", "rk45"}}), InputError);
  EXPECT_THROW(AcrobotConfig::fromParams({{"substeps", "1.5"}}), InputError);
}

TEST(Acrobot, HugeAnglesAreWrappedQuickly) {
  Acrobot a;
  a.setState(std::vector<double>{1e12, -1e12, 0, 0});
  const double tau = 0.0;
  a.step(std::span<const double>(&tau, 1));
  EXPECT_LE(std::fabs(a.state()[0]), std::numbers::pi);
  EXPECT_LE(std::fabs(a.state()[1]), std::numbers::pi);
}

TEST(CartPole, ResetDrawsFromPlusMinusPointZeroFive) {
  CartPole c;
  Rng rng(4);
  for (int i = 0; i < 200; ++i) {
    c.reset(rng);
    for (double v : c.state()) EXPECT_LE(std::fabs(v), 0.05);
  }
}

TEST(CartPole, SameSeedSameTrajectoryOtherSeedOther) {
  CartPole a, b;
  EXPECT_EQ(rollout(a, 5, 100), rollout(b, 5, 100));
  EXPECT_NE(rollout(a, 5, 100), rollout(b, 6, 100));
}

TEST(CartPole, FailsBeyondTheBoundsAndStillPaysTheStep) {
  CartPole c;
  const double f = 0.0;
  // Threshold on the angle: 12 degrees = 0.20943951023931953 rad, strict inequality.
  c.setState(std::vector<double>{0, 0, 0.25, 0});
  StepResult r = c.step(std::span<const double>(&f, 1));
  EXPECT_TRUE(r.terminated);
  EXPECT_EQ(r.reward, 1.0);
  c.setState(std::vector<double>{2.39, 1.0, 0, 0});  // x = 2.41 after the step.
  r = c.step(std::span<const double>(&f, 1));
  EXPECT_TRUE(r.terminated);
  c.setState(std::vector<double>{-2.39, -1.0, 0, 0});
  EXPECT_TRUE(c.step(std::span<const double>(&f, 1)).terminated);
  c.setState(std::vector<double>{0, 0, 0, 0});
  EXPECT_FALSE(c.step(std::span<const double>(&f, 1)).terminated);
}

TEST(CartPole, TruncatesAtMaxSteps) {
  CartPole c;  // Default limit: 1000 steps. Upright at rest with zero force stays upright.
  c.setState(std::vector<double>{0, 0, 0, 0});
  const double f = 0.0;
  StepResult r;
  for (int t = 0; t < 1000; ++t) {
    ASSERT_FALSE(r.truncated);
    r = c.step(std::span<const double>(&f, 1));
  }
  EXPECT_TRUE(r.truncated);
  EXPECT_FALSE(r.terminated);
}

TEST(CartPole, EulerUsesTheOldStateForEveryRightHandSide) {
  CartPole c;
  const std::vector<double> s{0.1, 0.2, 0.05, -0.3};
  c.setState(s);
  const double force = 4.0;
  const auto d = c.derivative({s[0], s[1], s[2], s[3]}, force);
  c.step(std::span<const double>(&force, 1));
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(c.state()[i], s[i] + 0.02 * d[i]);
}

TEST(CartPole, DiscreteForcesAndGravityParameter) {
  CartPole d(CartPoleConfig::fromParams({{"actions", "discrete"}}));
  EXPECT_EQ(d.forceOf(std::vector<double>{0}), -10.0);
  EXPECT_EQ(d.forceOf(std::vector<double>{1}), 10.0);
  EXPECT_THROW(d.forceOf(std::vector<double>{2}), InputError);
  CartPole g(CartPoleConfig::fromParams({{"gravity", "9.81"}}));
  const auto a = g.derivative({0, 0, 0.1, 0}, 0.0);
  const auto b = CartPole().derivative({0, 0, 0.1, 0}, 0.0);
  EXPECT_GT(std::fabs(a[3]), std::fabs(b[3]));
}

}  // namespace
}  // namespace gpfd::env
