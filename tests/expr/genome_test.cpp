#include "gpfd/expr/genome.hpp"

#include <gtest/gtest.h>

#include "gpfd/expr/eval.hpp"
#include "gpfd/expr/parse.hpp"

namespace gpfd::expr {
namespace {

const VariableNames kNames{"a", "b"};

TEST(Genome, LinearEncodingWithBoundaries) {
  Genome g;
  g.addFeature(parseInfix("a + sin(b)", kNames));
  g.addFeature(parseInfix("2", kNames));
  EXPECT_EQ(g.featureCount(), 2u);
  EXPECT_EQ(g.size(), 5u);
  EXPECT_EQ(g.starts(), (std::vector<std::uint32_t>{0, 4}));
  EXPECT_EQ(g.nodes()[0].length, 4u);
  EXPECT_EQ(g.nodes()[2].op, Op::Sin);
  EXPECT_EQ(g.nodes()[2].length, 2u);
  const double state[] = {1.0, 0.5};
  double out[2];
  evaluate(g, state, out);
  EXPECT_EQ(out[0], 1.0 + gpfd::expr::trig::sin(0.5));
  EXPECT_EQ(out[1], 2.0);
}

TEST(Genome, DepthCountsLevels) {
  EXPECT_EQ(depth(parseInfix("a", kNames)), 1);
  EXPECT_EQ(depth(parseInfix("a + b", kNames)), 2);
  EXPECT_EQ(depth(parseInfix("(a + b) * sin(a)", kNames)), 3);
  const Tree t = parseInfix("(a + b) * sin(a)", kNames);
  EXPECT_EQ(levelOf(t, 0), 1);
  EXPECT_EQ(levelOf(t, 2), 3);
  EXPECT_EQ(levelOf(t, 4), 2);
}

TEST(Genome, CheckFindsEveryProblem) {
  Genome g;
  g.addFeature(parseInfix("a * (b + 1)", kNames));
  EXPECT_EQ(checkGenome(g, {1, 4, 8, 64}, 2), "");
  EXPECT_NE(checkGenome(g, {2, 4, 8, 64}, 2).find("outside"), std::string::npos);
  EXPECT_NE(checkGenome(g, {1, 4, 2, 64}, 2).find("depth 3 exceeds 2"), std::string::npos);
  EXPECT_NE(checkGenome(g, {1, 4, 8, 4}, 2).find("size 5 exceeds 4"), std::string::npos);
  EXPECT_NE(checkGenome(g, {1, 4, 8, 64}, 1).find("out of range"), std::string::npos);
  Tree broken{Node::function(Op::Add), Node::variable(0)};
  EXPECT_FALSE(recomputeLengths(broken));
}

}  // namespace
}  // namespace gpfd::expr
