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
