#include "gpfd/expr/simplify.hpp"

#include <algorithm>

namespace gpfd::expr {
namespace {

bool isConstant(const Tree& t, double v) {
  return t.size() == 1 && t[0].op == Op::Const && t[0].value == v;
}
bool isConstant(const Tree& t) { return t.size() == 1 && t[0].op == Op::Const; }

// Structural equality (ops, variables and constant values); lengths follow from the ops.
bool sameTree(const Tree& a, const Tree& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const Node& x, const Node& y) {
    return x.op == y.op && x.var == y.var && x.value == y.value;
  });
}

Tree withRoot(Op op, const std::vector<Tree>& children) {
  Tree out{Node::function(op)};
  for (const auto& c : children) out.insert(out.end(), c.begin(), c.end());
  recomputeLengths(out);
  return out;
}

Tree simplifyAt(TreeView tree, std::size_t i) {
  const Node& node = tree[i];
  if (isTerminal(node.op)) return {node};
  std::vector<Tree> kids;
  std::size_t child = i + 1;
  for (int c = 0; c < arity(node.op); ++c) {
    kids.push_back(simplifyAt(tree, child));
    child += tree[child].length;
  }
  if (std::all_of(kids.begin(), kids.end(), [](const Tree& t) { return isConstant(t); })) {
    const double v = kids.size() == 1 ? apply(node.op, kids[0][0].value)
                                      : apply(node.op, kids[0][0].value, kids[1][0].value);
    return {Node::constant(v)};
  }
  if (kids.size() == 1) {
    const Tree& a = kids[0];
    if (node.op == Op::Neg && a[0].op == Op::Neg) return Tree(a.begin() + 1, a.end());
    if (node.op == Op::Abs && a[0].op == Op::Abs) return a;
    return withRoot(node.op, kids);
  }
  const Tree& a = kids[0];
  const Tree& b = kids[1];
  switch (node.op) {
    case Op::Add:
      if (isConstant(a, 0.0)) return b;
      if (isConstant(b, 0.0)) return a;
      break;
    case Op::Sub:
      if (isConstant(b, 0.0)) return a;
      if (sameTree(a, b)) return {Node::constant(0.0)};
      break;
    case Op::Mul:
      if (isConstant(a, 1.0)) return b;
      if (isConstant(b, 1.0)) return a;
      if (isConstant(a, 0.0) || isConstant(b, 0.0)) return {Node::constant(0.0)};
      break;
    case Op::Div:
      if (isConstant(b, 1.0)) return a;
      if (sameTree(a, b)) return {Node::constant(1.0)};
      break;
    case Op::Min:
    case Op::Max:
      if (sameTree(a, b)) return a;
      break;
    case Op::AbsDiff:
      if (sameTree(a, b)) return {Node::constant(0.0)};
      break;
    default:
      break;
  }
  return withRoot(node.op, kids);
}

}  // namespace

Tree simplify(TreeView tree) { return tree.empty() ? Tree{} : simplifyAt(tree, 0); }

Genome simplify(const Genome& genome) {
  Genome out;
  for (std::size_t k = 0; k < genome.featureCount(); ++k)
    out.addFeature(simplify(genome.feature(k)));
  return out;
}

}  // namespace gpfd::expr
