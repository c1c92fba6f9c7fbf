#include "gpfd/run/statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace gpfd::run {
namespace {

TEST(Statistics, SummaryWithStudentInterval) {
  const auto s = summarize({1, 2, 3, 4, 5});
  EXPECT_EQ(s.n, 5);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_NEAR(s.stddev, 1.5811388300841898, 1e-12);
  // t(0.975, 4) = 2.7764451051977987.
  EXPECT_NEAR(s.halfWidth, 2.7764451051977987 * 1.5811388300841898 / std::sqrt(5.0), 1e-9);
}

// Reference values computed by hand from the textbook formulas (Welch 1947; Mann & Whitney 1947
// with the normal approximation and continuity correction).
TEST(Statistics, WelchAndMannWhitneyOnSeparatedSamples) {
  const auto c = compare({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10});
  EXPECT_NEAR(c.welchT, -5.0, 1e-12);
  EXPECT_NEAR(c.welchDf, 8.0, 1e-12);
  EXPECT_NEAR(c.welchP, 0.0010528257934054874, 1e-9);
  EXPECT_DOUBLE_EQ(c.mannWhitneyU, 0.0);
  // z = (12.5 - 0.5) / sqrt(25 * 11 / 12) = 2.5067...; p = 2 (1 - Phi(z)).
  EXPECT_NEAR(c.mannWhitneyP, 0.012185, 1e-5);
  EXPECT_NEAR(c.cohenD, -5.0 / 1.5811388300841898, 1e-12);
  EXPECT_DOUBLE_EQ(c.a12, 0.0);
}

TEST(Statistics, IdenticalSamplesAreNotDifferent) {
  const auto c = compare({3, 1, 2, 2}, {2, 2, 1, 3});
  EXPECT_NEAR(c.welchP, 1.0, 1e-12);
  EXPECT_NEAR(c.mannWhitneyP, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(c.a12, 0.5);
  const auto constant = compare({4, 4, 4}, {4, 4, 4});
  EXPECT_EQ(constant.welchP, 1.0);
}

}  // namespace
}  // namespace gpfd::run
