// The one number parser: what it accepts, what it refuses, and the messages and places.
#include "gpfd/util/number.hpp"

#include <gtest/gtest.h>

#include "gpfd/util/error.hpp"

namespace gpfd {
namespace {

TEST(Number, AcceptsDecimalNumbersWithSurroundingSpace) {
  EXPECT_EQ(parseNumber("0.2", "w"), 0.2);
  EXPECT_EQ(parseNumber("+1e-5", "w"), 1e-5);
  EXPECT_EQ(parseNumber(" -3 ", "w"), -3.0);
  EXPECT_EQ(parseNumber("12.5\n", "w"), 12.5);  // A one-line file.
  EXPECT_EQ(parseInteger("+7", "w"), 7);
  EXPECT_EQ(parseInteger("-12", "w"), -12);
}

TEST(Number, RefusesAnythingElseNamingThePlace) {
  for (const char* bad :
       {"", " ", "abc", "1,5", "0x10", "inf", "nan", "-inf", "1e999", "1.5x", "+-1", "--1"}) {
    try {
      parseNumber(bad, "acrobot.dt");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "acrobot.dt");
      EXPECT_EQ(std::string(e.what()), "'" + std::string(bad) + "' is not a finite number");
    }
  }
  for (const char* bad : {"", "1.5", "1e3", "x", "99999999999999999999"}) {
    EXPECT_THROW(parseInteger(bad, "w"), InputError) << bad;
  }
}

TEST(Number, DurationsAreSecondsOrUnitsLargestFirst) {
  EXPECT_EQ(parseDuration("90", "w"), 90.0);
  EXPECT_EQ(parseDuration("2.5", "w"), 2.5);
  EXPECT_EQ(parseDuration("90s", "w"), 90.0);
  EXPECT_EQ(parseDuration("10m", "w"), 600.0);
  EXPECT_EQ(parseDuration(" 1h ", "w"), 3600.0);
  EXPECT_EQ(parseDuration("1h30m", "w"), 5400.0);
  EXPECT_EQ(parseDuration("1m30s", "w"), 90.0);
  EXPECT_EQ(parseDuration("2.5m", "w"), 150.0);
  for (const char* bad : {"", " ", "0", "0s", "-5", "10x", "m", "1m1h", "1m1m", "1h-30m", "inf",
                          "1e999", "10 minutes", "s10"}) {
    try {
      parseDuration(bad, "--time-budget");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "--time-budget");
      EXPECT_NE(std::string(e.what()).find("a duration is seconds (90) or numbers with h, m or s"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(Number, RangesNameTheParameterAndTheRange) {
  EXPECT_EQ(parseNumber("1", 0.0, 1.0, "p", "w"), 1.0);
  try {
    parseNumber("1e300", 1e-4, 10.0, "dt", "acrobot.dt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "dt must lie in [0.0001, 10], got 1e300 (acrobot.dt)");
  }
  EXPECT_THROW(parseInteger("0", 1, 5, "n", "w"), InputError);
  EXPECT_EQ(parseInteger("5", 1, 5, "n", "w"), 5);
}

TEST(Number, TextReadsBackExactly) {
  for (double v : {0.2, 1e-5, 0.1 + 0.2, 1.0 / 3.0, -2.5e300, 5e-324}) {
    EXPECT_EQ(parseNumber(numberText(v), "w"), v) << numberText(v);
  }
  EXPECT_EQ(numberText(0.2), "0.2");
  EXPECT_EQ(numberText(100.0), "100");
}

}  // namespace
}  // namespace gpfd
