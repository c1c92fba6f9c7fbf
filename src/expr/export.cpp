#include "gpfd/expr/export.hpp"

#include <fmt/format.h>

#include <cctype>
#include <string_view>
#include <utility>

#include "gpfd/expr/trig.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::expr {
namespace {

// Helper names of the generated code, per operator (C and Python share them).
std::string helper(Op op) { return "gpfd_" + std::string(info(op).name); }

// fmt::format rather than "literal" + temporary string in this file: GCC 12 at -O3 reports a
// false -Wrestrict (an overlap of 2^63 bytes) inside std::string's insert for the latter.
std::string variableComment(const Node& n, const VariableNames& names) {
  return n.var < names.size() ? names[n.var] : fmt::format("x{}", n.var);
}

// Prints a tree as nested helper calls; `variable` prints a variable node.
template <typename VariableText>
std::string calls(TreeView t, std::size_t i, const VariableText& variable) {
  const Node& n = t[i];
  if (n.op == Op::Const) return formatNumber(n.value);
  if (n.op == Op::Var) return variable(n);
  std::string out = helper(n.op) + "(";
  std::size_t child = i + 1;
  for (int c = 0; c < arity(n.op); ++c) {
    if (c > 0) out += ", ";
    out += calls(t, child, variable);
    child += t[child].length;
  }
  return out + ")";
}

std::string latexName(const std::string& name) {
  std::size_t digits = name.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(name[digits - 1]))) --digits;
  std::string stem;
  for (char c : name.substr(0, digits)) stem += c == '_' ? std::string("\\_") : std::string(1, c);
  std::string out = "\\mathit{" + stem + "}";
  if (digits < name.size()) out += "_{" + name.substr(digits) + "}";
  return out;
}

// `afterOperator` as in print.cpp's infix: the text follows a binary operator's symbol.
std::string latex(TreeView t, std::size_t i, const VariableNames& names, int parentPrecedence,
                  bool right, bool afterOperator) {
  const Node& n = t[i];
  if (n.op == Op::Const) return formatConstant(n.value, afterOperator, "\\left(", "\\right)");
  if (n.op == Op::Var) {
    return n.var < names.size() ? latexName(names[n.var]) : "x_{" + std::to_string(n.var) + "}";
  }
  const std::size_t a = i + 1;
  const std::size_t b = arity(n.op) == 2 ? a + t[a].length : a;
  const auto arg = [&](std::size_t c) { return latex(t, c, names, 0, false, false); };
  switch (n.op) {
    case Op::Add:
    case Op::Sub:
    case Op::Mul: {
      const int p = info(n.op).precedence;
      const char* symbol = n.op == Op::Add ? " + " : n.op == Op::Sub ? " - " : " \\cdot ";
      const bool parens = p < parentPrecedence || (p == parentPrecedence && right);
      std::string s = latex(t, a, names, p, false, afterOperator && !parens) + symbol +
                      latex(t, b, names, p, true, true);
      return parens ? "\\left(" + s + "\\right)" : s;
    }
    case Op::Div:
      return "\\frac{" + arg(a) + "}{" + arg(b) + "}";
    case Op::Min:
      return "\\min\\left(" + arg(a) + ", " + arg(b) + "\\right)";
    case Op::Max:
      return "\\max\\left(" + arg(a) + ", " + arg(b) + "\\right)";
    case Op::AbsDiff:
      return "\\left|" + arg(a) + " - " + arg(b) + "\\right|";
    case Op::Sqrt:
      return "\\sqrt{\\left|" + arg(a) + "\\right|}";
    case Op::Abs:
      return "\\left|" + arg(a) + "\\right|";
    case Op::Neg:
      return "-\\left(" + arg(a) + "\\right)";
    case Op::Square:
      return "\\left(" + arg(a) + "\\right)^2";
    case Op::Log:
      return "\\log\\left|" + arg(a) + "\\right|";
    default:
      return fmt::format("\\{}\\left({}\\right)", info(n.op).name, arg(a));
  }
}

// The preambles below name gpfd's constants as @NAME@; preamble() writes their exact values.
constexpr const char* kCPreamble =
    R"(/* Features discovered by gpfd. Protected semantics (gpfd docs/expressions.md): every value
   is finite; overflow saturates to +-DBL_MAX; a / b = 1 when |b| <= @NEAR_ZERO@; sqrt and log take |a|;
   log is 0 near 0; inputs: NaN -> 0, +-inf -> +-DBL_MAX. Compile with -fno-builtin (so that the
   compiler does not fold sin/cos/... of constants with its own, differently rounded, library) and
   without -ffast-math, and the values are bit-identical to gpfd's. */
#include <float.h>
#include <math.h>
#include <string.h>

static double gpfd_min(double a, double b) { return a < b ? a : b; }
static double gpfd_max(double a, double b) { return a > b ? a : b; }
static double gpfd_sat(double x) { return gpfd_min(gpfd_max(x, -DBL_MAX), DBL_MAX); }
static double gpfd_in(double x) { return x == x ? gpfd_sat(x) : 0.0; }
static double gpfd_add(double a, double b) { return gpfd_sat(a + b); }
static double gpfd_sub(double a, double b) { return gpfd_sat(a - b); }
static double gpfd_mul(double a, double b) { return gpfd_sat(a * b); }
static double gpfd_div(double a, double b) { return fabs(b) > @NEAR_ZERO@ ? gpfd_sat(a / b) : 1.0; }
static double gpfd_absdiff(double a, double b) { return gpfd_sat(fabs(a - b)); }
/* gpfd's sin and cos (gpfd include/gpfd/expr/trig.hpp): Cody-Waite reduction by pi/2 in three
   parts and fdlibm's kernel polynomials; the C library only for |a| > @LARGE@. */
static double gpfd_trig(double a, unsigned offset) {
  double shifted, k, r1, w, r2, tail, r, y, z, v, p, value;
  unsigned long long bits;
  unsigned q;
  if (fabs(a) < @TINY@) return offset == 0 ? a : 1.0;
  if (!(fabs(a) <= @LARGE@)) return offset == 0 ? sin(a) : cos(a);
  shifted = a * @TWO_OVER_PI@ + @ROUND_MAGIC@;
  memcpy(&bits, &shifted, sizeof bits);
  q = (unsigned)((bits + offset) & 3u);
  k = (shifted - @ROUND_MAGIC@) + 0.0;
  r1 = a - k * @PIO2_1@;
  w = k * @PIO2_2@;
  r2 = r1 - w;
  tail = ((r1 - r2) - w) - k * @PIO2_3@;
  r = r2 + tail;
  y = (r2 - r) + tail;
  z = r * r;
  if (q & 1u) {
    p = z * (@C1@ + z * (@C2@ +
        z * (@C3@ + z * (@C4@ +
        z * (@C5@ + z * @C6@)))));
    w = 1.0 - 0.5 * z;
    value = w + (((1.0 - w) - 0.5 * z) + (z * p - r * y));
  } else {
    v = z * r;
    p = @S2@ + z * (@S3@ +
        z * (@S4@ + z * (@S5@ +
        z * @S6@)));
    value = r - ((z * (0.5 * y - v * p) - y) - v * @S1@);
  }
  return (q & 2u) ? -value : value;
}
static double gpfd_sin(double a) { return gpfd_trig(a, 0); }
static double gpfd_cos(double a) { return gpfd_trig(a, 1); }
static double gpfd_tanh(double a) { return tanh(a); }
static double gpfd_sqrt(double a) { return sqrt(fabs(a)); }
static double gpfd_neg(double a) { return -a; }
static double gpfd_abs(double a) { return fabs(a); }
static double gpfd_exp(double a) { return gpfd_sat(exp(a)); }
static double gpfd_log(double a) { return fabs(a) > @NEAR_ZERO@ ? log(fabs(a)) : 0.0; }
static double gpfd_square(double a) { return gpfd_sat(a * a); }
)";

constexpr const char* kPythonPreamble =
    R"("""Features discovered by gpfd, with gpfd's protected semantics (docs/expressions.md):
every value is finite; overflow saturates to +-DBL_MAX; a / b = 1 when |b| <= @NEAR_ZERO@; sqrt and log
take |a|; log is 0 near 0; inputs: NaN -> 0, +-inf -> +-DBL_MAX. Arithmetic, sin and cos are
bit-identical to gpfd's (for |a| <= @LARGE@); tanh, exp and log are NumPy's and may differ from C's
libm in the last bit."""
import numpy as np

_MAX = np.finfo(np.float64).max


def _sat(x):
    return np.clip(x, -_MAX, _MAX)


def _in(x):
    x = np.asarray(x, dtype=np.float64)
    return np.where(np.isnan(x), 0.0, _sat(x))


def gpfd_add(a, b): return _sat(np.add(a, b))
def gpfd_sub(a, b): return _sat(np.subtract(a, b))
def gpfd_mul(a, b): return _sat(np.multiply(a, b))
def gpfd_min(a, b): return np.where(np.less(a, b), a, b)
def gpfd_max(a, b): return np.where(np.greater(a, b), a, b)
def gpfd_absdiff(a, b): return _sat(np.abs(np.subtract(a, b)))
def gpfd_tanh(a): return np.tanh(a)
def gpfd_sqrt(a): return np.sqrt(np.abs(a))
def gpfd_neg(a): return np.negative(a)
def gpfd_abs(a): return np.abs(a)
def gpfd_square(a): return _sat(np.multiply(a, a))


def gpfd_div(a, b):
    with np.errstate(all="ignore"):
        return np.where(np.abs(b) > @NEAR_ZERO@, _sat(np.divide(a, b)), 1.0)


def gpfd_exp(a):
    with np.errstate(over="ignore"):
        return _sat(np.exp(a))


def gpfd_log(a):
    with np.errstate(divide="ignore"):
        return np.where(np.abs(a) > @NEAR_ZERO@, np.log(np.abs(a)), 0.0)


def _trig(a, offset):
    """gpfd's sin (offset 0) and cos (offset 1), include/gpfd/expr/trig.hpp, bit for bit."""
    a = np.asarray(a, dtype=np.float64)
    shifted = a * @TWO_OVER_PI@ + @ROUND_MAGIC@
    q = (shifted.view(np.uint64) + np.uint64(offset)) & np.uint64(3)
    k = (shifted - @ROUND_MAGIC@) + 0.0
    r1 = a - k * @PIO2_1@
    w = k * @PIO2_2@
    r2 = r1 - w
    tail = ((r1 - r2) - w) - k * @PIO2_3@
    r = r2 + tail
    y = (r2 - r) + tail
    z = r * r
    v = z * r
    p = @S2@ + z * (@S3@ + z * (
        @S4@ + z * (@S5@ + z * @S6@)))
    sin_r = r - ((z * (0.5 * y - v * p) - y) - v * @S1@)
    c = z * (@C1@ + z * (@C2@ + z * (
        @C3@ + z * (@C4@ + z * (
            @C5@ + z * @C6@)))))
    cw = 1.0 - 0.5 * z
    cos_r = cw + (((1.0 - cw) - 0.5 * z) + (z * c - r * y))
    value = np.where((q & np.uint64(1)) == 1, cos_r, sin_r)
    value = np.where((q & np.uint64(2)) == 2, -value, value)
    large = ~(np.abs(a) <= @LARGE@)
    if np.any(large):
        value = np.where(large, np.sin(a) if offset == 0 else np.cos(a), value)
    return np.where(np.abs(a) < @TINY@, a if offset == 0 else 1.0, value)


def gpfd_sin(a): return _trig(a, 0)
def gpfd_cos(a): return _trig(a, 1)

)";

// A double as a C and Python literal that reads back exactly (shortest round trip, with a
// decimal point so that it is a floating-point literal in both languages).
std::string literal(double value) {
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

// The preamble with every @NAME@ replaced by the value of the constant it names.
std::string preamble(std::string text) {
  using namespace trig;
  const std::pair<const char*, double> constants[] = {
      {"@NEAR_ZERO@", protect::kNearZero},
      {"@TINY@", kTiny},
      {"@LARGE@", kLargeArgument},
      {"@ROUND_MAGIC@", kRoundMagic},
      {"@TWO_OVER_PI@", kTwoOverPi},
      {"@PIO2_1@", kPio2Part1},
      {"@PIO2_2@", kPio2Part2},
      {"@PIO2_3@", kPio2Part3},
      {"@S1@", kS1},
      {"@S2@", kS2},
      {"@S3@", kS3},
      {"@S4@", kS4},
      {"@S5@", kS5},
      {"@S6@", kS6},
      {"@C1@", kC1},
      {"@C2@", kC2},
      {"@C3@", kC3},
      {"@C4@", kC4},
      {"@C5@", kC5},
      {"@C6@", kC6},
  };
  for (const auto& [name, value] : constants) {
    const std::string replacement = literal(value);
    for (std::size_t at = text.find(name); at != std::string::npos;
         at = text.find(name, at + replacement.size())) {
      text.replace(at, std::string_view(name).size(), replacement);
    }
  }
  return text;
}

}  // namespace

std::string exportC(const Genome& genome, const VariableNames& names) {
  std::string out = preamble(kCPreamble);
  out +=
      fmt::format("\n/* {} features of {} state variables:", genome.featureCount(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) out += fmt::format(" s[{}] = {};", i, names[i]);
  out += " */\nvoid gpfd_features(const double* s, double* f) {\n";
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    out += fmt::format("  f[{}] = {};\n", k, calls(genome.feature(k), 0, [&](const Node& n) {
                         return fmt::format("gpfd_in(s[{}] /* {} */)", n.var,
                                            variableComment(n, names));
                       }));
  }
  return out + "}\n";
}

std::string exportPython(const Genome& genome, const VariableNames& names) {
  std::string out = preamble(kPythonPreamble);
  out += "\ndef features(s):\n    \"\"\"s[..., i] is state variable i:";
  for (std::size_t i = 0; i < names.size(); ++i) out += fmt::format(" {}={}", i, names[i]);
  out += fmt::format(
      ".\n\n    Returns one float64 array of shape s.shape[:-1] + ({},): feature k in [..., "
      "k].\"\"\"\n",
      genome.featureCount());
  out += "    s = np.asarray(s, dtype=np.float64)\n";
  out += fmt::format("    out = np.empty(s.shape[:-1] + ({},), dtype=np.float64)\n",
                     genome.featureCount());
  out += "    with np.errstate(all=\"ignore\"):  # Overflow saturates by design.\n";
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    out += fmt::format("        out[..., {}] = ", k) +
           calls(genome.feature(k), 0,
                 [&](const Node& n) { return fmt::format("_in(s[..., {}])", n.var); }) +
           "\n";
  }
  return out + "    return out\n";
}

std::string exportLatex(const Genome& genome, const VariableNames& names) {
  std::string out = "\\begin{align*}\n";
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    out += fmt::format("  \\phi_{{{}}}(s) &= {}{}\n", k + 1,
                       latex(genome.feature(k), 0, names, 0, false, false),
                       k + 1 < genome.featureCount() ? " \\\\" : "");
  }
  return out + "\\end{align*}\n";
}

std::string exportAs(const Genome& genome, const VariableNames& names, const std::string& format) {
  if (format == "c") return exportC(genome, names);
  if (format == "python") return exportPython(genome, names);
  if (format == "latex") return exportLatex(genome, names);
  if (format != "infix" && format != "sexpr") {
    throw InputError("unknown format '" + format + "' (infix, sexpr, c, python, latex)", "format");
  }
  std::string text;
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    text += (format == "sexpr" ? toSexpr(genome.feature(k), names)
                               : toInfix(genome.feature(k), names)) +
            "\n";
  }
  return text;
}

}  // namespace gpfd::expr
