#include <gtest/gtest.h>

#include "gpfd/expr/parse.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/util/error.hpp"
#include "test_genomes.hpp"

namespace gpfd::expr {
namespace {

const VariableNames kNames{"th1", "th2", "dth1", "dth2"};

TEST(Print, InfixUsesMinimalParentheses) {
  EXPECT_EQ(toInfix(parseInfix("(th1 + th2) * dth1", kNames), kNames), "(th1 + th2) * dth1");
  EXPECT_EQ(toInfix(parseInfix("th1 + th2 * dth1", kNames), kNames), "th1 + th2 * dth1");
  EXPECT_EQ(toInfix(parseInfix("(th1 - th2) - dth1", kNames), kNames), "th1 - th2 - dth1");
  EXPECT_EQ(toInfix(parseInfix("th1 - (th2 - dth1)", kNames), kNames), "th1 - (th2 - dth1)");
  EXPECT_EQ(toInfix(parseInfix("th1 / (th2 * 2)", kNames), kNames), "th1 / (th2 * 2)");
  EXPECT_EQ(toInfix(parseInfix("sin(th1 + 1) * -0.5", kNames), kNames), "sin(th1 + 1) * -0.5");
  EXPECT_EQ(toInfix(parseInfix("-th1", kNames), kNames), "neg(th1)");
  EXPECT_EQ(toInfix(parseInfix("absdiff(x[0], x[3])", kNames), kNames), "absdiff(th1, dth2)");
}

TEST(Print, Sexpr) {
  EXPECT_EQ(toSexpr(parseInfix("sin(th1) * (th2 - 2)", kNames), kNames), "(* (sin th1) (- th2 2))");
  EXPECT_EQ(parseSexpr("(* (sin th1) (- th2 2))", kNames),
            parseInfix("sin(th1) * (th2 - 2)", kNames));
  EXPECT_EQ(parseSexpr("(max -1.5 x[2])", kNames), parseInfix("max(-1.5, dth1)", kNames));
}

TEST(Print, RoundTripOnRandomGenomes) {
  Rng rng(42);
  const auto space = testing::everyOperator(4);
  for (int i = 0; i < 3000; ++i) {
    const Genome g = gp::randomGenome(rng, space);
    for (std::size_t k = 0; k < g.featureCount(); ++k) {
      const Tree original(g.feature(k).begin(), g.feature(k).end());
      const std::string infix = toInfix(original, kNames);
      ASSERT_EQ(parseInfix(infix, kNames), original) << infix;
      const std::string sexpr = toSexpr(original, kNames);
      ASSERT_EQ(parseSexpr(sexpr, kNames), original) << sexpr;
    }
  }
}

// Expects parsing to fail with a message containing `what` at line 1, column `column`.
void expectError(const std::string& text, const std::string& what, int column, bool sexpr = false,
                 int maxDepth = kMaxParseDepth) {
  try {
    if (sexpr) {
      parseSexpr(text, kNames, {"f", 1}, maxDepth);
    } else {
      parseInfix(text, kNames, {"f", 1}, maxDepth);
    }
    FAIL() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.message();
    EXPECT_EQ(e.where(), "f:1:" + std::to_string(column)) << e.message();
  }
}

TEST(Parse, MalformedInputNamesTheErrorAndPlace) {
  expectError("th1 + frob(th2)", "unknown operator 'frob'", 7);
  expectError("th1 + omega", "unknown variable 'omega'", 7);
  expectError("sin(th1, th2)", "wrong arity", 1);
  expectError("max(th1)", "wrong arity", 1);
  expectError("th1 * x[4]", "variable index 4 out of range", 7);
  expectError("x[99999999999]", "out of range", 1);
  expectError("", "empty", 1);
  expectError("   ", "empty", 1);
  expectError("th1 +", "empty expression", 6);
  expectError("(th1 + th2", "expected ')'", 11);
  expectError("th1 th2", "unexpected text", 5);
  expectError("1e999", "number out of range", 1);
  expectError("2x", "malformed number", 1);
  expectError("sin(sin(sin(th1)))", "too deep", 1, false, 3);
  expectError(std::string(500, '(') + "th1" + std::string(500, ')'), "too deep", 129);
  expectError("(sin th1 th2)", "wrong arity", 2, true);
  expectError("(frob th1)", "unknown operator 'frob'", 2, true);
  expectError("(+ th1 x[7])", "out of range", 8, true);
  expectError("(+ th1", "expected ')'", 7, true);
  expectError("", "empty", 1, true);
}

TEST(Parse, ErrorsCountLinesFromThePlace) {
  try {
    parseInfix("th1 +\n  bogus", kNames, {"file.features", 7});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "file.features:8:3");
  }
}

TEST(Parse, VariableNamedXStillParsesAsAName) {
  const VariableNames cartpole{"x", "dx", "th", "dth"};
  EXPECT_EQ(parseInfix("x * x[2]", cartpole), parseInfix("x * x[2]", cartpole));
  const Tree t = parseInfix("x + dx", cartpole);
  EXPECT_EQ(t[1].var, 0);
  EXPECT_EQ(toInfix(t, cartpole), "x + dx");
}

}  // namespace
}  // namespace gpfd::expr
