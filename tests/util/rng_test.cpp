#include "gpfd/util/rng.hpp"

#include <gtest/gtest.h>

#include <set>

namespace gpfd {
namespace {

TEST(Rng, SameSeedSameStream) {
  Rng a(99), b(99), c(100);
  for (int i = 0; i < 100; ++i) {
    const auto x = a();
    EXPECT_EQ(x, b());
    EXPECT_NE(x, c());
  }
}

TEST(Rng, DrawsStayInRange) {
  Rng rng(1);
  std::set<std::uint64_t> seen;
  for (int i = 0; i < 10000; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    const auto k = rng.below(7);
    ASSERT_LT(k, 7u);
    seen.insert(k);
    const int j = rng.between(-2, 2);
    ASSERT_GE(j, -2);
    ASSERT_LE(j, 2);
  }
  EXPECT_EQ(seen.size(), 7u);
}

TEST(Rng, NormalHasUnitMoments) {
  Rng rng(4);
  double sum = 0, sq = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = rng.normal();
    sum += x;
    sq += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sq / n, 1.0, 0.02);
}

TEST(Rng, DerivedSeedsDependOnEveryIndex) {
  std::set<std::uint64_t> seeds;
  for (int g = 0; g < 10; ++g) {
    for (int i = 0; i < 10; ++i) seeds.insert(deriveSeed(1, g, i));
  }
  EXPECT_EQ(seeds.size(), 100u);
  EXPECT_NE(deriveSeed(1, 2, 3), deriveSeed(1, 3, 2));
  EXPECT_EQ(deriveSeed(5, 1, 2), deriveSeed(5, 1, 2));
}

TEST(Rng, StateRoundTrip) {
  Rng a(8);
  a.normal();
  const auto saved = a.state();
  const double next = a.normal();
  Rng b(0);
  b.setState(saved);
  EXPECT_EQ(b.normal(), next);
}

}  // namespace
}  // namespace gpfd
