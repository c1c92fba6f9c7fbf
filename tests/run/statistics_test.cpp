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

// Reference values from SciPy 1.17 (scipy.stats.ttest_rel, scipy.stats.wilcoxon).
TEST(Statistics, PairedTTest) {
  const auto c = comparePaired({1, 2, 3, 4, 5}, {1.5, 2.1, 2.8, 4.9, 5.2});
  EXPECT_EQ(c.n, 5);
  EXPECT_NEAR(c.meanDifference, -0.3, 1e-12);
  EXPECT_NEAR(c.standardError, std::sqrt(0.175 / 5), 1e-12);
  EXPECT_NEAR(c.p, 0.18407403195057676, 1e-9);
  EXPECT_EQ(comparePaired({1, 2}, {1, 2}).p, 1.0);
  EXPECT_EQ(comparePaired({2, 3}, {1, 2}).p, 0.0);
  EXPECT_EQ(comparePaired({1}, {0}).p, 1.0);
}

TEST(Statistics, WilcoxonSignedRankExact) {
  EXPECT_NEAR(wilcoxonSignedRank({1, 2, 3, 4, 5, 6, 7, 8}).p, 0.0078125, 1e-12);
  EXPECT_NEAR(wilcoxonSignedRank({1.5, -0.5, 2, 3, 4, 5, 6, 7}).p, 0.015625, 1e-12);
  const auto t = wilcoxonSignedRank({-1, 2, 3, 4, 5, 6, 7, 8});
  EXPECT_NEAR(t.p, 0.015625, 1e-12);
  EXPECT_EQ(t.n, 8);
  EXPECT_DOUBLE_EQ(t.wPlus, 35.0);
  EXPECT_DOUBLE_EQ(t.median, 4.5);
  // Zeros are dropped: what remains is one positive value, p = 1.
  const auto zeros = wilcoxonSignedRank({0, 0, 3});
  EXPECT_EQ(zeros.n, 1);
  EXPECT_NEAR(zeros.p, 1.0, 1e-12);
  EXPECT_EQ(wilcoxonSignedRank({}).p, 1.0);
  // Ties: |-1| = |1| share rank 1.5; the sign patterns with W+ <= 1.5 are {} and either one
  // alone (W+ = 1.5), 3 of 2^3 = 8; p = 2 * 3 / 8 = 0.75.
  EXPECT_NEAR(wilcoxonSignedRank({-1, 1, 5}).p, 0.75, 1e-12);
}

TEST(Statistics, WilcoxonSignedRankNormalApproximation) {
  std::vector<double> values;
  for (int i = 1; i <= 40; ++i) values.push_back((i - 1) % 3 == 0 ? -i : i);
  EXPECT_NEAR(wilcoxonSignedRank(values).p, 0.09964873997927338, 1e-9);
}

}  // namespace
}  // namespace gpfd::run
