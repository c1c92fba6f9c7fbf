#include "gpfd/rl/features.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "gpfd/util/rng.hpp"

namespace gpfd::rl {
namespace {

TEST(FeaturePipeline, AppendsBias) {
  const features::RawFeatureMap raw(2);
  FeaturePipeline features(raw, {.bias = true, .normalise = false});
  ASSERT_EQ(features.dim(), 3u);
  const double state[2] = {4.0, -2.0};
  double out[3];
  ASSERT_TRUE(features.evaluate(state, out));
  EXPECT_EQ(out[0], 4.0);
  EXPECT_EQ(out[1], -2.0);
  EXPECT_EQ(out[2], 1.0);
}

TEST(FeaturePipeline, ReportsNonFinite) {
  const features::RawFeatureMap raw(2);
  FeaturePipeline features(raw, {});
  const double state[4] = {1.0, 2.0, std::numeric_limits<double>::infinity(), 0.0};
  double out[6];
  EXPECT_TRUE(features.evaluate(state, out));
  EXPECT_FALSE(features.evaluateBatch(state, 2, out));
}

// A NaN or infinity in any position fails the row and leaves the statistics alone: the moments
// after good rows and bad ones are those of the good rows.
TEST(FeaturePipeline, NonFiniteRowsFailAndAreNotCounted) {
  const features::RawFeatureMap raw(3);
  const FeatureOptions options{.bias = true, .normalise = true};
  FeaturePipeline withBad(raw, options), goodOnly(raw, options);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double good[2][3] = {{1.0, 2.0, 3.0}, {3.0, 0.0, -1.0}};
  const double bad[3][3] = {{nan, 2.0, 3.0}, {1.0, -inf, 3.0}, {1.0, 2.0, nan}};
  double out[4];
  for (const auto& row : good) {
    ASSERT_TRUE(withBad.evaluate(row, out));
    ASSERT_TRUE(goodOnly.evaluate(row, out));
  }
  for (const auto& row : bad) {
    EXPECT_FALSE(withBad.evaluate(row, out));
    double copy[4] = {row[0], row[1], row[2], 0.0};
    EXPECT_FALSE(withBad.transform(copy));
  }
  double w1[4] = {1.0, 1.0, 1.0, 0.0}, w2[4] = {1.0, 1.0, 1.0, 0.0};
  withBad.refresh(w1, 1);
  goodOnly.refresh(w2, 1);
  EXPECT_EQ(withBad.shift(), goodOnly.shift());
  EXPECT_EQ(withBad.scale(), goodOnly.scale());
}

TEST(FeaturePipeline, RefreshNormalisesAndKeepsOutputs) {
  const features::RawFeatureMap raw(2);
  FeaturePipeline features(raw, {.bias = true, .normalise = true});
  Rng rng(4);
  double out[3];
  for (int i = 0; i < 1000; ++i) {
    const double state[2] = {rng.normal(5.0, 3.0), rng.normal(-1.0, 0.1)};
    features.evaluate(state, out);
  }
  double weights[3] = {0.5, -2.0, 0.25};
  const double probe[2] = {4.0, -0.9};
  features.evaluate(probe, out);
  const double before = weights[0] * out[0] + weights[1] * out[1] + weights[2] * out[2];
  features.refresh(weights, 1);
  features.evaluate(probe, out);
  const double after = weights[0] * out[0] + weights[1] * out[1] + weights[2] * out[2];
  EXPECT_NEAR(after, before, 1e-9);
  // Now normalised: the probe's first feature is about (4 - 5) / 3.
  EXPECT_NEAR(out[0], -1.0 / 3.0, 0.05);
  EXPECT_NEAR(out[1], 1.0, 0.2);
}

}  // namespace
}  // namespace gpfd::rl
