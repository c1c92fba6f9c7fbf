// expr: the operators of feature functions, with their protected semantics defined once here and
// shared by the interpreter, the JIT, the simplifier, the printers and the exporters.
//
// Protected semantics (total: every operator maps finite values to finite values):
// - Every state variable entering a feature is sanitised: NaN -> 0, +-inf -> +-DBL_MAX.
// - Results that overflow saturate to +-DBL_MAX (add, sub, mul, div, square, exp, absdiff).
// - Division by a near-zero denominator (|b| <= kNearZero, NaN included) returns 1 (Koza 1992).
// - sqrt(a) = sqrt(|a|); log(a) = log(|a|), and 0 when |a| <= kNearZero.
// - min(a, b) = a < b ? a : b and max(a, b) = a > b ? a : b: the x86 minsd/maxsd rule, so that
//   native code gives bit-identical results.
// Hence a feature's value is always finite, and algebraic identities such as x - x = 0 hold for
// every input, which is what lets the simplifier rewrite them.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>

#include "gpfd/expr/trig.hpp"

namespace gpfd::expr {

enum class Op : std::uint8_t {
  // Terminals.
  Const,
  Var,
  // Binary.
  Add,
  Sub,
  Mul,
  Div,
  Min,
  Max,
  AbsDiff,
  // Unary.
  Sin,
  Cos,
  Sqrt,
  Neg,
  Abs,
  Exp,
  Log,
  Tanh,
  Square,
};
inline constexpr int kOpCount = static_cast<int>(Op::Square) + 1;

struct OpInfo {
  std::string_view name;   // Function name in S-expressions and infix calls ("add", "sin").
  std::string_view sexpr;  // Symbol in S-expressions ("+" for Add, else the name).
  int arity;
  int precedence;  // Infix binary operators: 1 for + -, 2 for * /; 0 for function calls.
  // Computed by a function call, not by a few instructions: gpfd's sin and cos (trig.hpp) and
  // libm's exp, log and tanh. Generated code calls the same function as the interpreter.
  bool call;
};

inline constexpr OpInfo kOpInfo[kOpCount] = {
    {"const", "const", 0, 0, false},     {"var", "var", 0, 0, false},
    {"add", "+", 2, 1, false},           {"sub", "-", 2, 1, false},
    {"mul", "*", 2, 2, false},           {"div", "/", 2, 2, false},
    {"min", "min", 2, 0, false},         {"max", "max", 2, 0, false},
    {"absdiff", "absdiff", 2, 0, false}, {"sin", "sin", 1, 0, true},
    {"cos", "cos", 1, 0, true},          {"sqrt", "sqrt", 1, 0, false},
    {"neg", "neg", 1, 0, false},         {"abs", "abs", 1, 0, false},
    {"exp", "exp", 1, 0, true},          {"log", "log", 1, 0, true},
    {"tanh", "tanh", 1, 0, true},        {"square", "square", 1, 0, false},
};

constexpr const OpInfo& info(Op op) { return kOpInfo[static_cast<int>(op)]; }
constexpr int arity(Op op) { return info(op).arity; }
constexpr bool isTerminal(Op op) { return arity(op) == 0; }
constexpr bool isCall(Op op) { return info(op).call; }

// Finds an operator by its name or S-expression symbol ("add" or "+"); terminals excluded.
std::optional<Op> opFromName(std::string_view name);

namespace protect {

inline constexpr double kMax = std::numeric_limits<double>::max();
// Denominators and logarithm arguments with magnitude at or below this count as zero.
inline constexpr double kNearZero = 1e-10;

// The x86 minsd/maxsd rule: the second operand when the comparison is false (NaN included).
inline double min(double a, double b) { return a < b ? a : b; }
inline double max(double a, double b) { return a > b ? a : b; }
// Clamps to [-DBL_MAX, DBL_MAX]; maps NaN to -DBL_MAX (the maxsd rule). Operands are finite under
// the protected semantics, so NaN never arises here in practice.
inline double saturate(double x) { return min(max(x, -kMax), kMax); }
// Applied to every state variable read by a feature.
inline double input(double x) { return x == x ? saturate(x) : 0.0; }

inline double add(double a, double b) { return saturate(a + b); }
inline double sub(double a, double b) { return saturate(a - b); }
inline double mul(double a, double b) { return saturate(a * b); }
inline double div(double a, double b) { return std::fabs(b) > kNearZero ? saturate(a / b) : 1.0; }
inline double absdiff(double a, double b) { return saturate(std::fabs(a - b)); }
inline double sqrt(double a) { return std::sqrt(std::fabs(a)); }
inline double exp(double a) { return saturate(std::exp(a)); }
inline double log(double a) { return std::fabs(a) > kNearZero ? std::log(std::fabs(a)) : 0.0; }
inline double square(double a) { return saturate(a * a); }

}  // namespace protect

// Applies a unary operator under the protected semantics.
inline double apply(Op op, double a) {
  switch (op) {
    case Op::Sin:
      return trig::sin(a);
    case Op::Cos:
      return trig::cos(a);
    case Op::Sqrt:
      return protect::sqrt(a);
    case Op::Neg:
      return -a;
    case Op::Abs:
      return std::fabs(a);
    case Op::Exp:
      return protect::exp(a);
    case Op::Log:
      return protect::log(a);
    case Op::Tanh:
      return std::tanh(a);
    case Op::Square:
      return protect::square(a);
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

// Applies a binary operator under the protected semantics.
inline double apply(Op op, double a, double b) {
  switch (op) {
    case Op::Add:
      return protect::add(a, b);
    case Op::Sub:
      return protect::sub(a, b);
    case Op::Mul:
      return protect::mul(a, b);
    case Op::Div:
      return protect::div(a, b);
    case Op::Min:
      return protect::min(a, b);
    case Op::Max:
      return protect::max(a, b);
    case Op::AbsDiff:
      return protect::absdiff(a, b);
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace gpfd::expr
