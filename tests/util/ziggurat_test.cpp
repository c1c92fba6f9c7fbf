// The ziggurat normal sampler: its tables describe 256 layers of equal area under exp(-x^2/2),
// and its draws follow N(0, 1) (moments, the Kolmogorov-Smirnov distance, the tail and wedge
// frequencies), with fixed seeds so that the checks are exact reruns.
#include "gpfd/util/ziggurat.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gpfd {
namespace {

using ziggurat::kLayerF;
using ziggurat::kLayerX;
using ziggurat::kTailStart;

double f(double x) { return std::exp(-0.5 * x * x); }

// Integral of f from r to infinity.
double tailArea(double r) { return std::sqrt(M_PI / 2) * std::erfc(r / std::sqrt(2.0)); }

double normalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

TEST(Ziggurat, LayersHaveEqualAreas) {
  const double v = kTailStart * f(kTailStart) + tailArea(kTailStart);
  EXPECT_NEAR(v, 0.00492867323399, 1e-13);  // Marsaglia & Tsang give 12 digits.
  EXPECT_EQ(kLayerX[1], kTailStart);
  EXPECT_NEAR(kLayerX[0] * f(kTailStart), v, 1e-15);
  for (int k = 1; k < 256; ++k) {
    ASSERT_GT(kLayerX[k], kLayerX[k + 1]) << k;
    ASSERT_NEAR(kLayerF[k], f(kLayerX[k]), 2e-16) << k;
    ASSERT_NEAR(kLayerX[k] * (kLayerF[k + 1] - kLayerF[k]), v, 1e-14) << "layer " << k;
  }
  EXPECT_EQ(kLayerX[256], 0.0);
  EXPECT_EQ(kLayerF[256], 1.0);
}

TEST(Ziggurat, SameStateSameDraws) {
  Rng a(17), b(17);
  for (int i = 0; i < 10000; ++i) ASSERT_EQ(standardNormal(a), standardNormal(b));
}

TEST(Ziggurat, DrawsFollowTheStandardNormal) {
  Rng rng(31);
  const int n = 400000;
  std::vector<double> x(n);
  double sum = 0, sq = 0, fourth = 0;
  int tail = 0, beyondTwo = 0;
  for (double& v : x) {
    v = standardNormal(rng);
    sum += v;
    sq += v * v;
    fourth += v * v * v * v;
    tail += std::fabs(v) > kTailStart;
    beyondTwo += std::fabs(v) > 2.0;
  }
  // Standard errors: mean 1/sqrt(n) = 0.0016, variance sqrt(2/n) = 0.0022, fourth moment
  // sqrt(96/n) = 0.015; the bounds are about 4 of them.
  EXPECT_NEAR(sum / n, 0.0, 0.0065);
  EXPECT_NEAR(sq / n, 1.0, 0.009);
  EXPECT_NEAR(fourth / n, 3.0, 0.06);
  // Tail |x| > r: expected n * 2 (1 - Phi(r)) = 103.3 (sd 10.2); |x| > 2: 18,200 (sd 132).
  const double pTail = 2 * (1 - normalCdf(kTailStart)), pTwo = 2 * (1 - normalCdf(2.0));
  EXPECT_NEAR(tail, n * pTail, 4 * std::sqrt(n * pTail));
  EXPECT_NEAR(beyondTwo, n * pTwo, 4 * std::sqrt(n * pTwo));
  // Kolmogorov-Smirnov: sqrt(n) D < 1.95 (p = 0.001).
  std::sort(x.begin(), x.end());
  double d = 0;
  for (int i = 0; i < n; ++i) {
    const double c = normalCdf(x[i]);
    d = std::max({d, c - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - c});
  }
  EXPECT_LT(std::sqrt(static_cast<double>(n)) * d, 1.95) << "D = " << d;
}

// The wedges (draws that fail the rectangle test) get the right share of each layer: the counts
// in fine bins around every layer edge follow the normal density.
TEST(Ziggurat, BinsAcrossTheLayerEdgesFollowTheDensity) {
  Rng rng(8);
  const int n = 1000000, bins = 120;
  const double width = 4.0 / bins;
  std::vector<int> count(bins, 0);
  for (int i = 0; i < n; ++i) {
    const double v = std::fabs(standardNormal(rng));
    if (v < 4.0) ++count[static_cast<int>(v / width)];
  }
  double chi2 = 0;
  for (int b = 0; b < bins; ++b) {
    const double expected = n * 2 * (normalCdf((b + 1) * width) - normalCdf(b * width));
    chi2 += (count[b] - expected) * (count[b] - expected) / expected;
  }
  // 120 degrees of freedom: the 0.999 quantile is 173.6.
  EXPECT_LT(chi2, 173.6);
}

}  // namespace
}  // namespace gpfd
