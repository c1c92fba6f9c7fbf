// Test helper: random genomes and edge-case states for the differential tests of the jit module.
// Self-contained on purpose (the GP module has its own generator).
#pragma once

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "gpfd/expr/genome.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::jit::testing {

using expr::Node;
using expr::Op;

// The operator sets of the paper's problems, plus every operator.
inline std::vector<Op> operatorSet(const std::string& name) {
  if (name == "arithmetic") return {Op::Add, Op::Sub, Op::Mul, Op::Div};
  if (name == "control") return {Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Sin, Op::Cos, Op::Sqrt};
  if (name == "tetris") return {Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Min, Op::Max, Op::AbsDiff};
  std::vector<Op> all;
  for (int i = 0; i < expr::kOpCount; ++i) {
    if (!expr::isTerminal(static_cast<Op>(i))) all.push_back(static_cast<Op>(i));
  }
  return all;
}

inline const std::vector<std::string>& operatorSetNames() {
  static const std::vector<std::string> names{"arithmetic", "control", "tetris", "all"};
  return names;
}

// Constants that stress the protected operators: zeros of both signs, the near-zero threshold,
// denormals, huge values, and ordinary draws.
inline double randomConstant(Rng& rng) {
  static const double special[] = {
      0.0,    -0.0,    1.0,    -1.0,  2.0,    1e-10, -1e-10, 1e-11,
      5e-324, -5e-324, 1e-300, 1e300, -1e300, 1e308, -1e308, std::numeric_limits<double>::max()};
  if (rng.bernoulli(0.3)) return special[rng.below(std::size(special))];
  return rng.bernoulli(0.5) ? rng.uniform() : rng.normal(0.0, 10.0);
}

inline void appendRandomTree(Rng& rng, const std::vector<Op>& ops, int depth, int variables,
                             bool full, expr::Tree& out) {
  const bool terminal = depth <= 1 || (!full && rng.bernoulli(0.3));
  if (terminal) {
    if (rng.bernoulli(0.6)) {
      out.push_back(Node::variable(static_cast<int>(rng.below(variables))));
    } else {
      out.push_back(Node::constant(randomConstant(rng)));
    }
    return;
  }
  const Op op = ops[rng.below(ops.size())];
  out.push_back(Node::function(op));
  // Occasionally repeat a subtree, so that shared sub-expressions occur.
  const std::size_t firstChild = out.size();
  appendRandomTree(rng, ops, depth - 1, variables, full, out);
  if (expr::arity(op) == 2) {
    if (rng.bernoulli(0.1)) {
      const expr::Tree copy(out.begin() + static_cast<std::ptrdiff_t>(firstChild), out.end());
      out.insert(out.end(), copy.begin(), copy.end());
    } else {
      appendRandomTree(rng, ops, depth - 1, variables, full, out);
    }
  }
}

// A tree of at most maxDepth levels ("grow"), or exactly maxDepth levels on every branch
// ("full"), with consistent subtree lengths.
inline expr::Tree randomTree(Rng& rng, const std::vector<Op>& ops, int maxDepth, int variables,
                             bool full = false) {
  expr::Tree tree;
  appendRandomTree(rng, ops, maxDepth, variables, full, tree);
  expr::recomputeLengths(tree);
  return tree;
}

// 1..maxFeatures features; now and then a feature repeats an earlier one or a subtree of it.
inline expr::Genome randomGenome(Rng& rng, const std::vector<Op>& ops, int maxFeatures,
                                 int maxDepth, int variables) {
  std::vector<expr::Tree> features;
  const int count = rng.between(1, maxFeatures);
  for (int k = 0; k < count; ++k) {
    if (k > 0 && rng.bernoulli(0.15)) {
      features.push_back(features[rng.below(features.size())]);
    } else {
      features.push_back(randomTree(rng, ops, rng.between(1, maxDepth), variables, false));
    }
  }
  return expr::Genome::fromFeatures(features);
}

// Values every state variable is tested with.
inline const std::vector<double>& edgeValues() {
  static const std::vector<double> values{0.0,
                                          -0.0,
                                          5e-324,
                                          -5e-324,
                                          2.2250738585072014e-308,
                                          1e-10,
                                          -1e-11,
                                          1.0,
                                          -2.5,
                                          1e308,
                                          -1e308,
                                          std::numeric_limits<double>::max(),
                                          std::numeric_limits<double>::infinity(),
                                          -std::numeric_limits<double>::infinity(),
                                          std::numeric_limits<double>::quiet_NaN(),
                                          -std::numeric_limits<double>::quiet_NaN()};
  return values;
}

// A state of `variables` values, each an edge value or an ordinary draw.
inline std::vector<double> randomState(Rng& rng, int variables) {
  std::vector<double> state(variables);
  for (double& x : state) {
    x = rng.bernoulli(0.5) ? edgeValues()[rng.below(edgeValues().size())] : rng.normal(0.0, 3.0);
  }
  return state;
}

// Bitwise equality, any NaN equal to any NaN.
inline bool sameBits(double a, double b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// The first n / 4 * 4 of n states (rows of `dim` values) as lane blocks
// (FeatureMap::evaluateLaneBlocks: variable i of state l at [(l / 4 * dim + i) * 4 + l % 4]).
inline std::vector<double> toLaneBlocks(const double* states, std::size_t n, std::size_t dim) {
  std::vector<double> blocks(n / 4 * 4 * dim);
  for (std::size_t l = 0; l < n / 4 * 4; ++l) {
    for (std::size_t i = 0; i < dim; ++i)
      blocks[(l / 4 * dim + i) * 4 + l % 4] = states[l * dim + i];
  }
  return blocks;
}

// Feature j of state l in lane blocks of k features.
inline double laneBlockValue(const double* blocks, std::size_t l, std::size_t j, std::size_t k) {
  return blocks[(l / 4 * k + j) * 4 + l % 4];
}

}  // namespace gpfd::jit::testing
