// One test per opcode: each operator alone, on variables and on constants, over every pair of
// edge values, through the fast interpreter, the scalar JIT and the batch kernel, against the
// reference interpreter bit for bit.
#include <gtest/gtest.h>

#include <vector>

#include "gpfd/expr/eval.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "random_genomes.hpp"

namespace gpfd::jit {
namespace {

using expr::Node;
using expr::Op;
using expr::Tree;

Tree make(std::vector<Node> nodes) {
  expr::recomputeLengths(nodes);
  return nodes;
}

// Features exercising `op`: on variables, on constants (folded at compile time), mixed, with the
// same operand twice (algebraic identities), and nested.
std::vector<Tree> featuresFor(Op op) {
  const Node x0 = Node::variable(0), x1 = Node::variable(1), f = Node::function(op);
  std::vector<Tree> out;
  if (op == Op::Const) {
    for (double c : {0.0, -0.0, 5e-324, 1e308, -1.5}) out.push_back(make({Node::constant(c)}));
    return out;
  }
  if (op == Op::Var) return {make({x0}), make({x1}), make({x0})};
  const double constants[] = {0.0, -0.0, 1.0, -1.0, 1e-11, 3.5, -1e300, 5e-324};
  if (expr::arity(op) == 1) {
    out.push_back(make({f, x0}));
    out.push_back(make({f, f, x1}));
    for (double c : constants) out.push_back(make({f, Node::constant(c)}));
    out.push_back(make({Node::function(Op::Add), f, x0, f, Node::function(Op::Neg), x0}));
    return out;
  }
  out.push_back(make({f, x0, x1}));
  out.push_back(make({f, x1, x0}));
  out.push_back(make({f, x0, x0}));
  for (double c : constants) {
    out.push_back(make({f, x0, Node::constant(c)}));
    out.push_back(make({f, Node::constant(c), x1}));
    out.push_back(make({f, Node::constant(c), Node::constant(-c * 3.0)}));
  }
  out.push_back(make({f, f, x0, x1, f, x1, Node::constant(2.0)}));
  return out;
}

class Opcode : public ::testing::TestWithParam<int> {};

TEST_P(Opcode, AgreesOnEveryPairOfEdgeValues) {
  const auto op = static_cast<Op>(GetParam());
  const expr::Genome genome = expr::Genome::fromFeatures(featuresFor(op));
  const std::size_t k = genome.featureCount();
  std::vector<double> states;
  for (double a : testing::edgeValues()) {
    for (double b : testing::edgeValues()) {
      states.insert(states.end(), {a, b});
    }
  }
  const std::size_t n = states.size() / 2;
  const CompiledFeatureMap compiled(genome, 2);
  const CompiledFeatureMap interpreted(genome, 2, CompileOptions{.native = false});
  if (jitAvailable()) {
    ASSERT_TRUE(compiled.isNative()) << compiled.fallbackReason();
  }
  std::vector<double> batch(n * k), blocks(n * k);
  compiled.evaluateBatch(states.data(), n, batch.data());
  const auto stateBlocks = testing::toLaneBlocks(states.data(), n, 2);
  compiled.evaluateLaneBlocks(stateBlocks.data(), n / 4, blocks.data());
  std::vector<double> expected(k), viaJit(k), viaFast(k);
  for (std::size_t i = 0; i < n; ++i) {
    const double* x = states.data() + 2 * i;
    expr::evaluate(genome, x, expected.data());
    compiled.evaluate(x, viaJit.data());
    interpreted.evaluate(x, viaFast.data());
    for (std::size_t j = 0; j < k; ++j) {
      ASSERT_TRUE(std::isfinite(expected[j]));
      ASSERT_TRUE(testing::sameBits(expected[j], viaJit[j]))
          << expr::info(op).name << " feature " << j << " state (" << x[0] << ", " << x[1]
          << "): " << expected[j] << " vs jit " << viaJit[j];
      ASSERT_TRUE(testing::sameBits(expected[j], viaFast[j]))
          << expr::info(op).name << " feature " << j << ": interp " << viaFast[j];
      ASSERT_TRUE(testing::sameBits(expected[j], batch[i * k + j]))
          << expr::info(op).name << " feature " << j << " state (" << x[0] << ", " << x[1]
          << "): " << expected[j] << " vs batch " << batch[i * k + j];
      if (i < n / 4 * 4) {
        ASSERT_TRUE(testing::sameBits(expected[j], testing::laneBlockValue(blocks.data(), i, j, k)))
            << expr::info(op).name << " feature " << j << " state (" << x[0] << ", " << x[1]
            << "): lane blocks";
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EveryOpcode, Opcode, ::testing::Range(0, expr::kOpCount),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return std::string(expr::info(static_cast<Op>(param.param)).name);
                         });

}  // namespace
}  // namespace gpfd::jit
