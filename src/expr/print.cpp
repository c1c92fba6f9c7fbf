#include "gpfd/expr/print.hpp"

#include <fmt/format.h>

#include <cmath>

namespace gpfd::expr {
namespace {

std::string variableName(const Node& node, const VariableNames& names) {
  if (node.var < names.size()) return names[node.var];
  return "x[" + std::to_string(node.var) + "]";
}

// Prints the subtree at `i`. A binary operator's text is parenthesised when it binds looser than
// its parent, or equally tight as a right operand (so that parsing rebuilds the same tree).
// `afterOperator`: the text follows a binary operator's symbol, where a negative constant is
// parenthesised ("x - (-0.5)", never "x - -0.5").
void infix(TreeView tree, std::size_t i, const VariableNames& names, int parentPrecedence,
           bool rightOperand, bool afterOperator, std::string& out) {
  const Node& node = tree[i];
  if (node.op == Op::Const) {
    out += formatConstant(node.value, afterOperator, "(", ")");
    return;
  }
  if (node.op == Op::Var) {
    out += variableName(node, names);
    return;
  }
  const OpInfo& op = info(node.op);
  const std::size_t first = i + 1;
  if (op.precedence > 0) {
    const bool parens =
        op.precedence < parentPrecedence || (op.precedence == parentPrecedence && rightOperand);
    if (parens) out += '(';
    infix(tree, first, names, op.precedence, false, afterOperator && !parens, out);
    out += ' ';
    out += op.sexpr;
    out += ' ';
    infix(tree, first + tree[first].length, names, op.precedence, true, true, out);
    if (parens) out += ')';
    return;
  }
  out += op.name;
  out += '(';
  std::size_t child = first;
  for (int c = 0; c < op.arity; ++c) {
    if (c > 0) out += ", ";
    infix(tree, child, names, 0, false, false, out);
    child += tree[child].length;
  }
  out += ')';
}

void sexpr(TreeView tree, std::size_t i, const VariableNames& names, std::string& out) {
  const Node& node = tree[i];
  if (node.op == Op::Const) {
    out += formatNumber(node.value);
    return;
  }
  if (node.op == Op::Var) {
    out += variableName(node, names);
    return;
  }
  out += '(';
  out += info(node.op).sexpr;
  std::size_t child = i + 1;
  for (int c = 0; c < arity(node.op); ++c) {
    out += ' ';
    sexpr(tree, child, names, out);
    child += tree[child].length;
  }
  out += ')';
}

}  // namespace

std::string formatNumber(double value) { return fmt::format("{}", value); }

std::string formatConstant(double value, bool afterOperator, std::string_view open,
                           std::string_view close) {
  if (!afterOperator || !std::signbit(value)) return formatNumber(value);
  return fmt::format("{}{}{}", open, formatNumber(value), close);
}

std::string toInfix(TreeView tree, const VariableNames& names) {
  std::string out;
  if (!tree.empty()) infix(tree, 0, names, 0, false, false, out);
  return out;
}

std::string toSexpr(TreeView tree, const VariableNames& names) {
  std::string out;
  if (!tree.empty()) sexpr(tree, 0, names, out);
  return out;
}

}  // namespace gpfd::expr
