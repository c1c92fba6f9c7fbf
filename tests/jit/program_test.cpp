// Lowering: constant folding, exact identities, shared sub-expressions.
#include "gpfd/jit/program.hpp"

#include <gtest/gtest.h>

#include "gpfd/expr/eval.hpp"

namespace gpfd::jit {
namespace {

using expr::Node;
using expr::Op;

expr::Tree make(std::vector<Node> nodes) {
  expr::recomputeLengths(nodes);
  return nodes;
}

const Node x0 = Node::variable(0), x1 = Node::variable(1), x2 = Node::variable(2);
Node fn(Op op) { return Node::function(op); }
Node c(double v) { return Node::constant(v); }

TEST(Lower, FoldsConstantSubtrees) {
  // (1 + 2) * x0 -> one constant, one variable, one multiplication.
  const auto p =
      lower(expr::Genome::fromFeatures({make({fn(Op::Mul), fn(Op::Add), c(1), c(2), x0})}), 1);
  ASSERT_EQ(p.code.size(), 3u);
  EXPECT_EQ(p.code[p.outputs[0]].op, Op::Mul);
  int constants = 0;
  for (const auto& in : p.code) constants += in.op == Op::Const && in.value == 3.0;
  EXPECT_EQ(constants, 1);
}

TEST(Lower, SharesSubexpressionsWithinAndAcrossFeatures) {
  // f0 = (x0 + x1) * (x1 + x0); f1 = (x0 + x1) * (x1 + x0) + x2.
  const auto sum = std::vector<Node>{fn(Op::Add), x0, x1};
  const auto sumSwapped = std::vector<Node>{fn(Op::Add), x1, x0};
  std::vector<Node> f0{fn(Op::Mul)};
  f0.insert(f0.end(), sum.begin(), sum.end());
  f0.insert(f0.end(), sumSwapped.begin(), sumSwapped.end());
  std::vector<Node> f1{fn(Op::Add)};
  f1.insert(f1.end(), f0.begin(), f0.end());
  f1.push_back(x2);
  const auto p = lower(expr::Genome::fromFeatures({make(f0), make(f1)}), 3);
  // x0, x1, x0+x1, (x0+x1)^2 as a product, x2, f1: six values.
  EXPECT_EQ(p.code.size(), 6u);
  EXPECT_EQ(
      p.code[p.code[p.outputs[1]].a].op == Op::Mul || p.code[p.code[p.outputs[1]].b].op == Op::Mul,
      true);
}

TEST(Lower, RemovesExactIdentitiesOnly) {
  const auto p = lower(expr::Genome::fromFeatures({
                           make({fn(Op::Sub), x0, x0}),           // +0
                           make({fn(Op::Div), x1, x1}),           // 1
                           make({fn(Op::Min), x0, x0}),           // x0
                           make({fn(Op::Neg), fn(Op::Neg), x1}),  // x1
                           make({fn(Op::Mul), x0, c(1.0)}),       // x0
                           make({fn(Op::Add), x0, c(0.0)}),       // kept: -0 + 0 = +0
                       }),
                       2);
  EXPECT_EQ(p.code[p.outputs[0]].op, Op::Const);
  EXPECT_EQ(p.code[p.outputs[1]].op, Op::Const);
  EXPECT_EQ(p.code[p.outputs[1]].value, 1.0);
  EXPECT_EQ(p.code[p.outputs[2]].op, Op::Var);
  EXPECT_EQ(p.code[p.outputs[3]].op, Op::Var);
  EXPECT_EQ(p.code[p.outputs[4]].op, Op::Var);
  EXPECT_EQ(p.code[p.outputs[5]].op, Op::Add);
}

TEST(Lower, KeepsOperandOrderOfMinAndMax) {
  // min(-0, +0) = +0 but min(+0, -0) = -0: the two must stay distinct.
  const auto p = lower(
      expr::Genome::fromFeatures({make({fn(Op::Min), x0, x1}), make({fn(Op::Min), x1, x0})}), 2);
  EXPECT_NE(p.outputs[0], p.outputs[1]);
  const double state[] = {-0.0, 0.0};
  double out[2];
  std::vector<double> scratch(p.code.size());
  run(p, state, out, scratch.data());
  EXPECT_FALSE(std::signbit(out[0]));
  EXPECT_TRUE(std::signbit(out[1]));
}

TEST(Lower, DropsDeadValuesAndKeepsOperandsFirst) {
  const auto p =
      lower(expr::Genome::fromFeatures({make({fn(Op::Mul), fn(Op::Sub), x0, x0, x1})}), 2);
  for (std::size_t i = 0; i < p.code.size(); ++i) {
    const int n = expr::arity(p.code[i].op);
    if (n >= 1) {
      EXPECT_LT(p.code[i].a, i);
    }
    if (n == 2) {
      EXPECT_LT(p.code[i].b, i);
    }
  }
  // (x0 - x0) * x1 = 0 * x1: x0 is dead (the product is kept, its sign depends on x1).
  for (const auto& in : p.code) EXPECT_FALSE(in.op == Op::Var && in.var == 0);
}

}  // namespace
}  // namespace gpfd::jit
