// The group-sequential confirmation's looks and boundaries (run/sequential_test.hpp).
#include <gtest/gtest.h>

#include <stdexcept>

#include "gpfd/run/sequential_test.hpp"

namespace gpfd::run {
namespace {

TEST(SequentialTest, LooksSplitTheSeedsEvenly) {
  EXPECT_EQ(seedsAtLook(20, 1, 3), 7);
  EXPECT_EQ(seedsAtLook(20, 2, 3), 14);
  EXPECT_EQ(seedsAtLook(20, 3, 3), 20);
  EXPECT_EQ(seedsAtLook(30, 1, 3), 10);
  EXPECT_EQ(seedsAtLook(30, 2, 3), 20);
  EXPECT_EQ(seedsAtLook(7, 1, 1), 7);
  EXPECT_THROW(seedsAtLook(20, 4, 3), std::invalid_argument);
  EXPECT_THROW(seedsAtLook(20, 1, kMaxLooks + 1), std::invalid_argument);
}

// O'Brien-Fleming, 3 looks, two-sided 0.05: boundaries 3.471, 2.454, 2.004 (Jennison & Turnbull
// 2000, Table 2.3), nominal levels 2 (1 - Phi(z)).
TEST(SequentialTest, NominalLevelsAreOBrienFlemings) {
  EXPECT_NEAR(nominalLevel(1, 1), 0.05, 1e-4);
  EXPECT_NEAR(nominalLevel(1, 3), 0.000518, 0.00001);
  EXPECT_NEAR(nominalLevel(2, 3), 0.0141, 0.0002);
  EXPECT_NEAR(nominalLevel(3, 3), 0.0451, 0.0002);
  for (int looks = 2; looks <= kMaxLooks; ++looks) {
    for (int k = 1; k < looks; ++k) EXPECT_LT(nominalLevel(k, looks), nominalLevel(k + 1, looks));
    EXPECT_LT(nominalLevel(looks, looks), 0.05);
  }
}

// With the no-learning reference, an early end needs a decision that more seeds would not
// change: the winner lost to the original variables, or it clearly differs from both.
TEST(SequentialTest, AConfirmationEndsEarlyOnlyWhenNoLearningIsDecidedToo) {
  const PairedComparison better{10, 2.0, 0.2, 0.0001}, worse{10, -2.0, 0.2, 0.0001},
      close{10, 0.5, 0.2, 0.03};
  EXPECT_TRUE(confirmationEndsAtLook(better, &better, 1, 3));
  EXPECT_TRUE(confirmationEndsAtLook(better, &worse, 1, 3));   // Clearly below no learning.
  EXPECT_FALSE(confirmationEndsAtLook(better, &close, 1, 3));  // Undecided against it.
  EXPECT_TRUE(confirmationEndsAtLook(worse, &close, 1, 3));    // Lost: nothing left to decide.
  EXPECT_FALSE(confirmationEndsAtLook(close, &better, 2, 3));
  EXPECT_TRUE(confirmationEndsAtLook(close, &close, 3, 3));    // The last look ends them.
  EXPECT_TRUE(confirmationEndsAtLook(better, nullptr, 1, 3));  // Without it: as endsAtLook.
  EXPECT_FALSE(confirmationEndsAtLook(close, nullptr, 1, 3));
}

TEST(SequentialTest, OnlyAClearDifferenceEndsEarly) {
  PairedComparison clear{10, 2.0, 0.2, 0.0001}, close{10, 0.5, 0.2, 0.03};
  EXPECT_TRUE(endsAtLook(clear, 1, 3));
  EXPECT_FALSE(endsAtLook(close, 1, 3));
  EXPECT_FALSE(endsAtLook(close, 2, 3));
  EXPECT_TRUE(endsAtLook(close, 3, 3));  // The last look always ends the trials.
  EXPECT_TRUE(endsAtLook(close, 1, 1));
}

}  // namespace
}  // namespace gpfd::run
