#include "gpfd/jit/program.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "gpfd/expr/ops.hpp"

namespace gpfd::jit {
namespace {

using expr::Op;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Builds the instruction list with value numbering: an open-addressing table maps each
// (op, operands, variable, constant bits) to the instruction that computes it.
class Builder {
 public:
  explicit Builder(std::size_t nodes) {
    std::size_t capacity = 16;
    while (capacity < 2 * nodes + 2) capacity *= 2;
    table_.assign(capacity, kEmpty);
    code_.reserve(nodes);
  }

  std::uint32_t constant(double v) { return intern({Op::Const, 0, 0, 0, v}); }
  std::uint32_t variable(std::uint16_t var) { return intern({Op::Var, var, 0, 0, 0.0}); }

  std::uint32_t unary(Op op, std::uint32_t a) {
    const Instr& x = code_[a];
    if (x.op == Op::Const) return constant(expr::apply(op, x.value));
    switch (op) {
      case Op::Neg:
        if (x.op == Op::Neg) return x.a;  // -(-x) = x.
        break;
      case Op::Abs:
        if (x.op == Op::Abs) return a;  // ||x|| = |x|.
        if (x.op == Op::Neg) return unary(Op::Abs, x.a);
        break;
      case Op::Sqrt:  // These read |x| only.
      case Op::Log:
        if (x.op == Op::Neg || x.op == Op::Abs) return unary(op, x.a);
        break;
      case Op::Square:  // (-x)^2 = |x|^2 = x^2 exactly.
        if (x.op == Op::Neg || x.op == Op::Abs) return unary(op, x.a);
        break;
      default:
        break;
    }
    return intern({op, 0, a, 0, 0.0});
  }

  std::uint32_t binary(Op op, std::uint32_t a, std::uint32_t b) {
    const Instr& x = code_[a];
    const Instr& y = code_[b];
    const bool xc = x.op == Op::Const, yc = y.op == Op::Const;
    if (xc && yc) return constant(expr::apply(op, x.value, y.value));
    // Operands are finite under the protected semantics, so each rewrite below is exact.
    switch (op) {
      case Op::Add:  // x + (-0) = x, including x = +-0.
        if (yc && bits(y.value) == bits(-0.0)) return a;
        if (xc && bits(x.value) == bits(-0.0)) return b;
        break;
      case Op::Sub:
        if (a == b) return constant(0.0);                // x - x = +0.
        if (yc && bits(y.value) == bits(0.0)) return a;  // x - (+0) = x.
        break;
      case Op::Mul:
        if (yc && y.value == 1.0) return a;
        if (xc && x.value == 1.0) return b;
        if (yc && y.value == -1.0) return unary(Op::Neg, a);
        if (xc && x.value == -1.0) return unary(Op::Neg, b);
        break;
      case Op::Div:
        if (a == b) return constant(1.0);  // x / x = 1, also when |x| is near zero.
        if (yc && !(std::fabs(y.value) > expr::protect::kNearZero)) return constant(1.0);
        if (yc && y.value == 1.0) return a;
        if (yc && isPowerOfTwo(y.value) && isPowerOfTwo(1.0 / y.value)) {
          // x / 2^k and x * 2^-k are the same real number, so they round to the same double:
          // a multiplication instead of a division, exactly.
          return binary(Op::Mul, a, constant(1.0 / y.value));
        }
        break;
      case Op::Min:
      case Op::Max:
        if (a == b) return a;
        break;
      case Op::AbsDiff:
        if (a == b) return constant(0.0);
        break;
      default:
        break;
    }
    // a + b, a * b and |a - b| are exactly commutative in IEEE arithmetic; min and max are not
    // (signed zeros), nor are the others.
    if ((op == Op::Add || op == Op::Mul || op == Op::AbsDiff) && a > b) std::swap(a, b);
    return intern({op, 0, a, b, 0.0});
  }

  std::vector<Instr>& code() { return code_; }

 private:
  // +-2^k, finite and nonzero (subnormal powers of two included).
  static bool isPowerOfTwo(double c) {
    int exponent = 0;
    return std::isfinite(c) && std::fabs(std::frexp(c, &exponent)) == 0.5;
  }

  static constexpr std::uint32_t kEmpty = 0xffffffffu;

  static bool same(const Instr& p, const Instr& q) {
    return p.op == q.op && p.var == q.var && p.a == q.a && p.b == q.b &&
           bits(p.value) == bits(q.value);
  }

  static std::uint64_t hash(const Instr& in) {
    std::uint64_t h = static_cast<std::uint64_t>(in.op) | (std::uint64_t{in.var} << 8);
    h ^= (std::uint64_t{in.a} << 24) ^ (std::uint64_t{in.b} << 44);
    h ^= bits(in.value) * 0x9e3779b97f4a7c15ULL;
    h ^= h >> 31;
    h *= 0xbf58476d1ce4e5b9ULL;
    return h ^ (h >> 29);
  }

  std::uint32_t intern(const Instr& in) {
    const std::size_t mask = table_.size() - 1;
    for (std::size_t slot = hash(in) & mask;; slot = (slot + 1) & mask) {
      const std::uint32_t id = table_[slot];
      if (id == kEmpty) {
        table_[slot] = static_cast<std::uint32_t>(code_.size());
        code_.push_back(in);
        return table_[slot];
      }
      if (same(code_[id], in)) return id;
    }
  }

  std::vector<Instr> code_;
  std::vector<std::uint32_t> table_;
};

void fail(std::size_t feature, const std::string& what) {
  throw LowerError("feature " + std::to_string(feature) + ": " + what);
}

// Genome-level limits, and feature boundaries inside the node array (so that feature views are
// safe to form); each tree is checked node by node while it is lowered.
void checkGenome(const expr::Genome& genome) {
  if (genome.featureCount() > kMaxLowerFeatures) {
    throw LowerError("genome has " + std::to_string(genome.featureCount()) +
                     " features, more than the limit of " + std::to_string(kMaxLowerFeatures));
  }
  if (genome.size() > kMaxLowerNodes) {
    throw LowerError("genome has " + std::to_string(genome.size()) +
                     " nodes, more than the limit of " + std::to_string(kMaxLowerNodes));
  }
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    const std::uint32_t start = genome.starts()[k];
    if (start >= genome.size() || genome.nodes()[start].length == 0 ||
        genome.nodes()[start].length > genome.size() - start) {
      fail(k, "length out of the genome");
    }
  }
}

}  // namespace

bool Program::hasCalls() const {
  for (const Instr& in : code) {
    if (expr::isCall(in.op)) return true;
  }
  return false;
}

Program lower(const expr::Genome& genome, std::size_t inputDim) {
  checkGenome(genome);
  Builder builder(genome.size());
  std::vector<std::uint32_t> outputs;
  outputs.reserve(genome.featureCount());
  // Reverse prefix order: operands are on the stack, first operand on top, with the length and
  // depth of their subtrees, which validates the tree in the same pass.
  struct Entry {
    std::uint32_t value;
    std::uint32_t length;
    int depth;
  };
  std::vector<Entry> stack;
  stack.reserve(64);
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    const expr::TreeView tree = genome.feature(k);
    stack.clear();
    for (std::size_t i = tree.size(); i-- > 0;) {
      const expr::Node& node = tree[i];
      if (static_cast<int>(node.op) >= expr::kOpCount) fail(k, "unknown operator");
      const int n = expr::arity(node.op);
      if (stack.size() < static_cast<std::size_t>(n)) fail(k, "malformed prefix tree");
      Entry e{0, 1, 0};
      switch (n) {
        case 0:
          if (node.op == Op::Var) {
            if (node.var >= inputDim) {
              fail(k, "variable x" + std::to_string(node.var) + " out of range (the state has " +
                          std::to_string(inputDim) + " variables)");
            }
            e.value = builder.variable(node.var);
          } else {
            if (!std::isfinite(node.value)) fail(k, "non-finite constant");
            e.value = builder.constant(node.value);
          }
          break;
        case 1:
          e = stack.back();
          stack.pop_back();
          e.value = builder.unary(node.op, e.value);
          e.length += 1;
          break;
        default: {
          const Entry a = stack.back();
          stack.pop_back();
          const Entry b = stack.back();
          stack.pop_back();
          e.value = builder.binary(node.op, a.value, b.value);
          e.length = 1 + a.length + b.length;
          e.depth = std::max(a.depth, b.depth);
        }
      }
      e.depth += 1;
      if (node.length != e.length) fail(k, "subtree lengths do not match the tree");
      if (e.depth > kMaxLowerDepth) {
        fail(k, "deeper than the limit of " + std::to_string(kMaxLowerDepth) + " levels");
      }
      stack.push_back(e);
    }
    if (stack.size() != 1) fail(k, "malformed prefix tree");
    outputs.push_back(stack.back().value);
  }

  // Keep what the outputs need, in the original order.
  std::vector<Instr>& all = builder.code();
  std::vector<std::uint32_t> index(all.size(), 0);
  std::vector<char> live(all.size(), 0);
  for (std::uint32_t o : outputs) live[o] = 1;
  for (std::size_t i = all.size(); i-- > 0;) {
    if (!live[i]) continue;
    const int n = expr::arity(all[i].op);
    if (n >= 1) live[all[i].a] = 1;
    if (n == 2) live[all[i].b] = 1;
  }
  Program program;
  program.inputDim = inputDim;
  program.nodeCount = genome.size();
  program.code.reserve(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (!live[i]) continue;
    Instr in = all[i];
    in.a = index[in.a];
    in.b = index[in.b];
    index[i] = static_cast<std::uint32_t>(program.code.size());
    program.code.push_back(in);
  }
  for (std::uint32_t o : outputs) program.outputs.push_back(index[o]);
  return program;
}

void run(const Program& program, const double* state, double* features, double* scratch) {
  namespace p = expr::protect;
  double* const v = scratch;  // v[i]: the value of instruction i.
  const Instr* code = program.code.data();
  const std::size_t n = program.code.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Instr& in = code[i];
    switch (in.op) {
      case Op::Const:
        v[i] = in.value;
        break;
      case Op::Var:
        v[i] = p::input(state[in.var]);
        break;
      case Op::Add:
        v[i] = p::add(v[in.a], v[in.b]);
        break;
      case Op::Sub:
        v[i] = p::sub(v[in.a], v[in.b]);
        break;
      case Op::Mul:
        v[i] = p::mul(v[in.a], v[in.b]);
        break;
      case Op::Div:
        v[i] = p::div(v[in.a], v[in.b]);
        break;
      case Op::Min:
        v[i] = p::min(v[in.a], v[in.b]);
        break;
      case Op::Max:
        v[i] = p::max(v[in.a], v[in.b]);
        break;
      case Op::AbsDiff:
        v[i] = p::absdiff(v[in.a], v[in.b]);
        break;
      case Op::Sin:
        v[i] = expr::trig::sin(v[in.a]);
        break;
      case Op::Cos:
        v[i] = expr::trig::cos(v[in.a]);
        break;
      case Op::Sqrt:
        v[i] = p::sqrt(v[in.a]);
        break;
      case Op::Neg:
        v[i] = -v[in.a];
        break;
      case Op::Abs:
        v[i] = std::fabs(v[in.a]);
        break;
      case Op::Exp:
        v[i] = p::exp(v[in.a]);
        break;
      case Op::Log:
        v[i] = p::log(v[in.a]);
        break;
      case Op::Tanh:
        v[i] = std::tanh(v[in.a]);
        break;
      case Op::Square:
        v[i] = p::square(v[in.a]);
        break;
    }
  }
  for (std::size_t k = 0; k < program.outputs.size(); ++k) features[k] = v[program.outputs[k]];
}

}  // namespace gpfd::jit
