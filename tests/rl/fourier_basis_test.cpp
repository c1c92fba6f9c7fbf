#include "gpfd/rl/fourier_basis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace gpfd::rl {
namespace {

TEST(FourierBasis, FullCouplingHasEveryCoefficientVector) {
  const FourierBasis basis({{-1, 1}, {0, 10}}, 3, FourierBasis::Coupling::Full);
  ASSERT_EQ(basis.outputDim(), 16u);
  // x = (0.25, 0.5) after scaling; c runs in base 4 with the first variable fastest.
  const double state[] = {-0.5, 5.0};
  std::vector<double> f(16);
  basis.evaluate(state, f.data());
  EXPECT_EQ(f[0], 1.0);  // c = (0, 0).
  for (int c1 = 0; c1 <= 3; ++c1) {
    for (int c0 = 0; c0 <= 3; ++c0) {
      EXPECT_NEAR(f[c0 + 4 * c1], std::cos(std::numbers::pi * (c0 * 0.25 + c1 * 0.5)), 1e-12);
    }
  }
}

TEST(FourierBasis, FullCouplingMatchesTheDefinitionInFourDimensions) {
  const FourierBasis basis({{-1, 1}, {0, 1}, {-3, 3}, {0, 2}}, 3, FourierBasis::Coupling::Full);
  const double state[] = {0.3, 0.9, -2.0, 1.7};
  const double x[] = {0.65, 0.9, 1.0 / 6.0, 0.85};
  std::vector<double> f(basis.outputDim());
  basis.evaluate(state, f.data());
  for (std::size_t t = 0; t < f.size(); ++t) {
    double dot = 0.0;
    std::size_t rest = t;
    for (int i = 0; i < 4; ++i, rest /= 4) dot += static_cast<double>(rest % 4) * x[i];
    EXPECT_NEAR(f[t], std::cos(std::numbers::pi * dot), 1e-12) << t;
  }
}

TEST(FourierBasis, IndependentWhenTheFullBasisIsTooLarge) {
  const std::vector<StateRange> ranges(8, {-1, 1});
  const auto basis = FourierBasis::automatic(ranges, 3);
  EXPECT_EQ(basis.coupling(), FourierBasis::Coupling::Independent);
  EXPECT_EQ(basis.outputDim(), 8u * 3u + 1u);
  EXPECT_EQ(FourierBasis::automatic({{0, 1}, {0, 1}, {0, 1}, {0, 1}}, 3).outputDim(), 256u);
}

TEST(FourierBasis, ClampsOutOfRangeAndNonFiniteInputs) {
  const FourierBasis basis({{0, 1}}, 2, FourierBasis::Coupling::Full);
  const double state[] = {std::nan("")};
  double f[3];
  basis.evaluate(state, f);
  for (double v : f) EXPECT_TRUE(std::isfinite(v));
  const double far[] = {1e300};
  basis.evaluate(far, f);
  EXPECT_NEAR(f[1], -1.0, 1e-15);  // cos(pi * 1).
}

}  // namespace
}  // namespace gpfd::rl
