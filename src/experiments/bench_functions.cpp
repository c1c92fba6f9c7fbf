#include "gpfd/experiments/bench_functions.hpp"

#include <vector>

namespace gpfd::experiments {
namespace {

using expr::Node;
using expr::Op;

void append(Rng& rng, BenchSet set, int depth, expr::Tree& out) {
  if (depth <= 1) {
    if (rng.bernoulli(0.5)) {
      out.push_back(Node::variable(static_cast<int>(rng.below(kBenchVariables))));
    } else {
      const std::uint64_t which = rng.below(3);
      out.push_back(Node::constant(which == 0 ? 1.0 : which == 1 ? 2.0 : rng.uniform()));
    }
    return;
  }
  static const Op arithmetic[] = {Op::Add, Op::Sub, Op::Mul, Op::Div};
  static const Op unary[] = {Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Sin, Op::Cos, Op::Sqrt};
  const Op op = set == BenchSet::Arithmetic ? arithmetic[rng.below(4)] : unary[rng.below(7)];
  out.push_back(Node::function(op));
  for (int c = 0; c < expr::arity(op); ++c) append(rng, set, depth - 1, out);
}

}  // namespace

std::string_view benchSetName(BenchSet set) {
  return set == BenchSet::Arithmetic ? "arithmetic" : "unary";
}

expr::Tree benchTree(std::uint64_t seed, BenchSet set, int depth, int run) {
  Rng rng(deriveSeed(seed, static_cast<int>(set), depth, run));
  expr::Tree tree;
  append(rng, set, depth, tree);
  expr::recomputeLengths(tree);
  return tree;
}

}  // namespace gpfd::experiments
