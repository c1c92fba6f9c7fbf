#include "gpfd/expr/eval.hpp"

namespace gpfd::expr {
namespace {

double walk(const Node* node, const double* state) {
  switch (node->op) {
    case Op::Const:
      return node->value;
    case Op::Var:
      return protect::input(state[node->var]);
    default:
      break;
  }
  const Node* first = node + 1;
  if (arity(node->op) == 1) return apply(node->op, walk(first, state));
  const double a = walk(first, state);
  const double b = walk(first + first->length, state);
  return apply(node->op, a, b);
}

}  // namespace

double evaluate(TreeView tree, const double* state) { return walk(tree.data(), state); }

void evaluate(const Genome& genome, const double* state, double* features) {
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    features[k] = evaluate(genome.feature(k), state);
  }
}

}  // namespace gpfd::expr
