// gpfd's own sin and cos (expr/trig.hpp): accuracy against long double, and the special cases
// that the JIT, the batch kernel and the exporters must reproduce.
#include "gpfd/expr/trig.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

namespace gpfd::expr::trig {
namespace {

// |got - reference| in units in the last place of the double nearest the reference.
double ulpError(double got, long double reference) {
  const double nearest = static_cast<double>(reference);
  const double ulp = std::nextafter(std::fabs(nearest), INFINITY) - std::fabs(nearest);
  return static_cast<double>(std::fabs((static_cast<long double>(got) - reference) / ulp));
}

TEST(Trig, WithinOneUlpUpToTheLargeArgumentBound) {
  std::mt19937_64 rng(7);
  for (double range : {0.8, 4.0, 1e3, kLargeArgument}) {
    std::uniform_real_distribution<double> uniform(-range, range);
    double worstSin = 0.0, worstCos = 0.0;
    for (int i = 0; i < 200000; ++i) {
      const double x = uniform(rng);
      worstSin = std::max(worstSin, ulpError(sin(x), sinl(static_cast<long double>(x))));
      worstCos = std::max(worstCos, ulpError(cos(x), cosl(static_cast<long double>(x))));
    }
    EXPECT_LT(worstSin, 1.0) << "range " << range;
    EXPECT_LT(worstCos, 1.0) << "range " << range;
  }
}

TEST(Trig, NearMultiplesOfHalfPi) {
  for (int k = -3000; k <= 3000; ++k) {
    const double m = k * 1.5707963267948966;
    for (double x : {m, std::nextafter(m, 1e9), std::nextafter(m, -1e9)}) {
      // Near a zero of sin or cos the relative error is what counts: compare in ulps as well.
      EXPECT_LT(ulpError(sin(x), sinl(static_cast<long double>(x))), 1.0) << x;
      EXPECT_LT(ulpError(cos(x), cosl(static_cast<long double>(x))), 1.0) << x;
    }
  }
}

TEST(Trig, SpecialCases) {
  EXPECT_EQ(std::bit_cast<std::uint64_t>(sin(-0.0)), std::bit_cast<std::uint64_t>(-0.0));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(sin(0.0)), 0u);
  EXPECT_EQ(cos(-0.0), 1.0);
  EXPECT_EQ(sin(5e-324), 5e-324);  // Denormal: sin x = x.
  EXPECT_EQ(sin(1e-9), 1e-9);
  EXPECT_EQ(cos(1e-9), 1.0);
  // Beyond the bound: the C library.
  EXPECT_EQ(sin(1e300), std::sin(1e300));
  EXPECT_EQ(cos(-1.7976931348623157e308), std::cos(-1.7976931348623157e308));
  EXPECT_TRUE(std::isnan(sin(NAN)));
  EXPECT_TRUE(std::isnan(cos(INFINITY)));
  // Odd and even.
  for (double x : {0.3, 2.0, 123.456, 999999.5}) {
    EXPECT_EQ(sin(-x), -sin(x));
    EXPECT_EQ(cos(-x), cos(x));
  }
}

}  // namespace
}  // namespace gpfd::expr::trig
