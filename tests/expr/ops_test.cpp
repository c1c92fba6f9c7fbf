#include "gpfd/expr/ops.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace gpfd::expr {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMax = std::numeric_limits<double>::max();

const double kEdges[] = {0.0,   -0.0,   1.0,  -1.0,  0.5,   1e-320, -1e-320, 1e-11, 3.0,
                         1e308, -1e308, kMax, -kMax, 710.0, -745.0, 1e154,   -7.25};

TEST(ProtectedOps, DivisionByNearZeroIsOne) {
  EXPECT_EQ(protect::div(3.0, 0.0), 1.0);
  EXPECT_EQ(protect::div(3.0, -0.0), 1.0);
  EXPECT_EQ(protect::div(3.0, 1e-11), 1.0);
  EXPECT_EQ(protect::div(3.0, kNaN), 1.0);
  EXPECT_EQ(protect::div(3.0, 2.0), 1.5);
}

TEST(ProtectedOps, SqrtAndLogOfNegatives) {
  EXPECT_EQ(protect::sqrt(-4.0), 2.0);
  EXPECT_EQ(protect::log(-std::exp(1.0)), std::log(std::exp(1.0)));
  EXPECT_EQ(protect::log(0.0), 0.0);
  EXPECT_EQ(protect::log(1e-12), 0.0);
}

TEST(ProtectedOps, OverflowSaturates) {
  EXPECT_EQ(protect::mul(1e200, 1e200), kMax);
  EXPECT_EQ(protect::mul(-1e200, 1e200), -kMax);
  EXPECT_EQ(protect::add(kMax, kMax), kMax);
  EXPECT_EQ(protect::exp(1000.0), kMax);
  EXPECT_EQ(protect::div(1e300, 1e-9), kMax);
  EXPECT_EQ(protect::square(1e200), kMax);
  EXPECT_EQ(protect::absdiff(kMax, -kMax), kMax);
}

TEST(ProtectedOps, InputsAreSanitised) {
  EXPECT_EQ(protect::input(kNaN), 0.0);
  EXPECT_EQ(protect::input(kInf), kMax);
  EXPECT_EQ(protect::input(-kInf), -kMax);
  EXPECT_EQ(protect::input(1.5), 1.5);
}

TEST(ProtectedOps, MinMaxFollowTheSecondOperandRule) {
  EXPECT_EQ(protect::min(1.0, 2.0), 1.0);
  EXPECT_EQ(protect::max(1.0, 2.0), 2.0);
  EXPECT_TRUE(std::signbit(protect::min(0.0, -0.0)));
  EXPECT_FALSE(std::signbit(protect::min(-0.0, 0.0)));
}

// Every operator maps finite operands to a finite value.
TEST(ProtectedOps, TotalOnFiniteValues) {
  for (int i = 0; i < kOpCount; ++i) {
    const Op op = static_cast<Op>(i);
    for (double a : kEdges) {
      if (arity(op) == 1) {
        EXPECT_TRUE(std::isfinite(apply(op, a))) << info(op).name << "(" << a << ")";
      }
      if (arity(op) == 2) {
        for (double b : kEdges) {
          EXPECT_TRUE(std::isfinite(apply(op, a, b)))
              << info(op).name << "(" << a << ", " << b << ")";
        }
      }
    }
  }
}

TEST(ProtectedOps, NamesResolve) {
  for (int i = 0; i < kOpCount; ++i) {
    const Op op = static_cast<Op>(i);
    if (isTerminal(op)) continue;
    EXPECT_EQ(opFromName(info(op).name), op);
    EXPECT_EQ(opFromName(info(op).sexpr), op);
  }
  EXPECT_FALSE(opFromName("frobnicate"));
  EXPECT_FALSE(opFromName("const"));
}

}  // namespace
}  // namespace gpfd::expr
