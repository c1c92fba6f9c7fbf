#include "gpfd/expr/simplify.hpp"

#include <gtest/gtest.h>

#include "gpfd/expr/eval.hpp"
#include "gpfd/expr/parse.hpp"
#include "test_genomes.hpp"

namespace gpfd::expr {
namespace {

const VariableNames kNames{"a", "b", "c"};

std::string simplified(const std::string& text) {
  return toInfix(simplify(parseInfix(text, kNames)), kNames);
}

TEST(Simplify, Rules) {
  EXPECT_EQ(simplified("(1 + 2) * a"), "3 * a");
  EXPECT_EQ(simplified("a - a"), "0");
  EXPECT_EQ(simplified("sin(a) * 1"), "sin(a)");
  EXPECT_EQ(simplified("1 * b"), "b");
  EXPECT_EQ(simplified("a + 0"), "a");
  EXPECT_EQ(simplified("0 + a"), "a");
  EXPECT_EQ(simplified("neg(neg(c))"), "c");
  EXPECT_EQ(simplified("(a * b) / (a * b)"), "1");
  EXPECT_EQ(simplified("b * (a - a)"), "0");
  EXPECT_EQ(simplified("min(a + 1, a + 1)"), "a + 1");
  EXPECT_EQ(simplified("absdiff(c, c) + b"), "b");
  EXPECT_EQ(simplified("a / (2 - 1)"), "a");
  EXPECT_EQ(simplified("sqrt(4) + a"), "2 + a");
  EXPECT_EQ(simplified("1 / 0"), "1");  // Protected division.
  EXPECT_EQ(simplified("a * b"), "a * b");
}

// Simplification never changes a value, on random genomes and states with edge values.
TEST(Simplify, PreservesValues) {
  Rng rng(7);
  const auto space = testing::everyOperator(3);
  int changed = 0;
  for (int i = 0; i < 4000; ++i) {
    // Few variables and small constants make repeated subtrees (x - x) common.
    const Genome g = gp::randomGenome(rng, space);
    const Genome s = simplify(g);
    ASSERT_EQ(s.featureCount(), g.featureCount());
    changed += s.size() != g.size();
    for (int t = 0; t < 8; ++t) {
      const auto state = testing::randomState(rng, 3);
      std::vector<double> before(g.featureCount()), after(g.featureCount());
      evaluate(g, state.data(), before.data());
      evaluate(s, state.data(), after.data());
      for (std::size_t k = 0; k < before.size(); ++k) {
        ASSERT_TRUE(std::isfinite(before[k]));
        ASSERT_EQ(before[k], after[k])
            << toInfix(g.feature(k), kNames) << " -> " << toInfix(s.feature(k), kNames);
      }
    }
  }
  EXPECT_GT(changed, 100);  // The rules did fire.
}

}  // namespace
}  // namespace gpfd::expr
