#include "gpfd/gp/operators.hpp"

#include <gtest/gtest.h>

#include "gpfd/gp/init.hpp"

namespace gpfd::gp {
namespace {

SearchSpace space(const std::string& primitives, expr::GenomeLimits limits) {
  SearchSpace s;
  s.primitives = expr::PrimitiveSet::named(primitives);
  s.variableCount = 4;
  s.limits = limits;
  s.initMaxDepth = limits.maxDepth;
  s.initMaxFeatures = limits.maxFeatures;
  return s;
}

void expectValid(const expr::Genome& g, const SearchSpace& s, const char* op) {
  const auto problem = expr::checkGenome(g, s.limits, s.variableCount);
  ASSERT_EQ(problem, "") << op;
  for (const auto& node : g.nodes()) {
    if (!expr::isTerminal(node.op)) {
      ASSERT_TRUE(s.primitives.contains(node.op)) << op;
    }
  }
}

// Every operator keeps every limit, over thousands of seeded applications on small and
// tight limits and both paper primitive sets.
TEST(Operators, KeepGenomesValid) {
  const std::vector<SearchSpace> spaces = {
      space("control", {1, 8, 8, 64}), space("tetris", {2, 5, 4, 9}), space("all", {1, 3, 6, 20})};
  Rng rng(2024);
  for (const auto& s : spaces) {
    std::vector<expr::Genome> pool;
    for (int i = 0; i < 40; ++i) {
      pool.push_back(randomGenome(rng, s));
      expectValid(pool.back(), s, "init");
    }
    for (int i = 0; i < 3000; ++i) {
      const auto& a = pool[rng.below(pool.size())];
      const auto& b = pool[rng.below(pool.size())];
      auto [c1, c2] = subtreeCrossover(rng, a, b, s);
      expectValid(c1, s, "subtree crossover");
      expectValid(c2, s, "subtree crossover");
      auto [l1, l2] = featureListCrossover(rng, a, b, s);
      expectValid(l1, s, "feature-list crossover");
      expectValid(l2, s, "feature-list crossover");
      ASSERT_EQ(l1.featureCount() + l2.featureCount(), a.featureCount() + b.featureCount());
      expectValid(nodeMutation(rng, a, s), s, "node mutation");
      expectValid(treeMutation(rng, a, s), s, "tree mutation");
      expectValid(shrinkage(rng, a, s), s, "shrinkage");
      pool[rng.below(pool.size())] = rng.bernoulli(0.5) ? c1 : l2;  // Let the pool drift.
    }
  }
}

TEST(Operators, FeatureListCrossoverFollowsFigure2) {
  const auto s = space("control", {1, 10, 8, 64});
  Rng rng(3);
  expr::Genome a, b;
  for (int k = 0; k < 4; ++k) a.addFeature(expr::Tree{expr::Node::constant(k)});
  for (int k = 0; k < 3; ++k) b.addFeature(expr::Tree{expr::Node::constant(10 + k)});
  for (int t = 0; t < 200; ++t) {
    auto [c1, c2] = featureListCrossover(rng, a, b, s);
    // c1 = a[0, i) + b[j, 3), c2 = b[0, j) + a[i, 4) with 0 < i < 4, 0 < j < 3.
    std::size_t i = 0;
    while (i < c1.featureCount() && c1.feature(i)[0].value < 10) ++i;
    const std::size_t j = 3 - (c1.featureCount() - i);
    ASSERT_GT(i, 0u);
    ASSERT_LT(i, 4u);
    ASSERT_GT(j, 0u);
    ASSERT_LT(j, 3u);
    for (std::size_t f = 0; f < c1.featureCount(); ++f) {
      ASSERT_EQ(static_cast<std::size_t>(c1.feature(f)[0].value), f < i ? f : 10 + j + (f - i));
    }
    for (std::size_t f = 0; f < c2.featureCount(); ++f) {
      ASSERT_EQ(static_cast<std::size_t>(c2.feature(f)[0].value), f < j ? 10 + f : i + (f - j));
    }
  }
}

TEST(Operators, ShrinkageReplacesAnOperatorByAChild) {
  const auto s = space("control", {1, 4, 8, 64});
  Rng rng(5);
  expr::Genome g;
  g.addFeature(expr::Tree{expr::Node{expr::Op::Sin, 0, 2, 0}, expr::Node::variable(1)});
  const auto shrunk = shrinkage(rng, g, s);
  ASSERT_EQ(shrunk.size(), 1u);
  EXPECT_EQ(shrunk.nodes()[0], expr::Node::variable(1));
}

TEST(Operators, NodeMutationKeepsArity) {
  const auto s = space("control", {1, 4, 8, 64});
  Rng rng(9);
  for (int t = 0; t < 500; ++t) {
    const auto g = randomGenome(rng, s);
    const auto m = nodeMutation(rng, g, s);
    ASSERT_EQ(m.size(), g.size());
    int differences = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
      if (!(g.nodes()[i] == m.nodes()[i])) {
        ++differences;
        ASSERT_EQ(expr::arity(g.nodes()[i].op), expr::arity(m.nodes()[i].op));
      }
    }
    ASSERT_LE(differences, 1);
  }
}

}  // namespace
}  // namespace gpfd::gp
