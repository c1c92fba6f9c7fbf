// expr: human-readable printing of feature functions, infix with minimal parentheses and
// S-expressions. parse.hpp reads both back to the identical tree.
#pragma once

#include <string>
#include <vector>

#include "gpfd/expr/genome.hpp"

namespace gpfd::expr {

// Variable names by index; indices without a name print as x[i].
using VariableNames = std::vector<std::string>;

// Infix: + - * / as binary operators (left-associative, * / binding tighter), everything else as
// calls such as sin(x) or min(a, b); negation prints as neg(x). Constants print in shortest
// round-trip form.
std::string toInfix(TreeView tree, const VariableNames& names);
// S-expression: (+ x (sin y)).
std::string toSexpr(TreeView tree, const VariableNames& names);
// A number in shortest round-trip form ("0.5", "1e-05").
std::string formatNumber(double value);

}  // namespace gpfd::expr
