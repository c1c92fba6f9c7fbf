// Bit-for-bit comparison of learning curves (tests of paths that must give the same numbers).
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

#include "gpfd/rl/learning_curve.hpp"

namespace gpfd::rl::testing {

inline bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// The same rows, counters, divergence and weights, bit for bit (wallSeconds aside).
inline void expectSameCurves(const LearningCurve& a, const LearningCurve& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].update, b.points[i].update);
    EXPECT_EQ(a.points[i].episodes, b.points[i].episodes);
    EXPECT_EQ(a.points[i].steps, b.points[i].steps) << "row " << i;
    EXPECT_TRUE(sameBits(a.points[i].meanReturn, b.points[i].meanReturn))
        << "row " << i << ": " << a.points[i].meanReturn << " vs " << b.points[i].meanReturn;
  }
  EXPECT_EQ(a.episodes, b.episodes);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.diverged, b.diverged);
  EXPECT_EQ(a.divergedReason, b.divergedReason);
  ASSERT_EQ(a.weights.values.size(), b.weights.values.size());
  for (std::size_t i = 0; i < a.weights.values.size(); ++i) {
    EXPECT_TRUE(sameBits(a.weights.values[i], b.weights.values[i])) << "weight " << i;
  }
  EXPECT_EQ(a.weights.shift, b.weights.shift);
  EXPECT_EQ(a.weights.scale, b.weights.scale);
}

}  // namespace gpfd::rl::testing
