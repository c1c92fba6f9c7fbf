// "Did you mean": edit distance and the closest plausible candidate.
#include "gpfd/io/suggest.hpp"

#include <gtest/gtest.h>

namespace gpfd::io {
namespace {

TEST(Suggest, EditDistanceCountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(editDistance("", ""), 0u);
  EXPECT_EQ(editDistance("abc", ""), 3u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("population", "populaton"), 1u);
}

TEST(Suggest, OffersOnlyPlausibleTypos) {
  const std::vector<std::string> keys{"population", "generations", "elitism"};
  EXPECT_EQ(closest("populaton", keys), "population");
  EXPECT_EQ(closest("generatoins", keys), "generations");
  EXPECT_EQ(closest("zzz", keys), "");
  EXPECT_EQ(didYouMean("elitsm", keys), " (did you mean 'elitism'?)");
  EXPECT_EQ(didYouMean("nothing-like-it", keys), "");
}

}  // namespace
}  // namespace gpfd::io
