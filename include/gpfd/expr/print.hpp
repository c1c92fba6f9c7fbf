// expr: human-readable printing of feature functions, infix with minimal parentheses and
// S-expressions. parse.hpp reads both back to the identical tree.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "gpfd/expr/genome.hpp"

namespace gpfd::expr {

// Variable names by index; indices without a name print as x[i].
using VariableNames = std::vector<std::string>;

// Infix: + - * / as binary operators (left-associative, * / binding tighter), everything else as
// calls such as sin(x) or min(a, b); negation prints as neg(x). Constants print in shortest
// round-trip form; a negative one right after an operator in parentheses: "x - (-0.5)".
std::string toInfix(TreeView tree, const VariableNames& names);
// S-expression: (+ x (sin y)).
std::string toSexpr(TreeView tree, const VariableNames& names);
// A number in shortest round-trip form ("0.5", "1e-05").
std::string formatNumber(double value);
// A constant operand as formatNumber prints it, wrapped in `open` and `close` when it is negative
// (sign bit set: -0 too) and follows a binary operator's symbol (`afterOperator`), so that no
// text reads "- -0.5", "+ -0.5" or "* -0.5".
std::string formatConstant(double value, bool afterOperator, std::string_view open,
                           std::string_view close);

}  // namespace gpfd::expr
