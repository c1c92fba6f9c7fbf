// jit: the straight-line program a genome lowers to before it is interpreted or compiled. Lowering
// folds constants, applies the algebraic identities that hold bit for bit under the protected
// semantics of expr/ops.hpp, and shares common sub-expressions within and across features, so
// that each distinct value is computed once per state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "gpfd/expr/genome.hpp"

namespace gpfd::jit {

// Hard limits of lowering (and hence of the interpreters and the JIT built on it). They equal the
// parse limits of expr, so every genome that can reach the system can be lowered; anything larger
// or deeper is refused before any code is generated.
inline constexpr int kMaxLowerDepth = expr::kMaxParseDepth;         // Levels per feature.
inline constexpr std::size_t kMaxLowerNodes = expr::kMaxParseSize;  // Nodes in the whole genome.
inline constexpr std::size_t kMaxLowerFeatures = 1 << 12;           // Features per genome.

// A genome (or call) that breaks a limit or is malformed: out-of-range variable, non-finite
// constant, inconsistent lengths, too deep or too large.
class LowerError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// One instruction: value[i] = op(value[a], value[b]) (binary), op(value[a]) (unary),
// the constant `value` (Const) or protect::input(state[var]) (Var). Operands always precede
// the instruction (a, b < i), so the list is in evaluation order.
struct Instr {
  expr::Op op = expr::Op::Const;
  std::uint16_t var = 0;
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  double value = 0.0;
};

struct Program {
  std::vector<Instr> code;             // Live instructions only, in evaluation order.
  std::vector<std::uint32_t> outputs;  // outputs[k] = index in `code` of feature k's value.
  std::size_t inputDim = 0;            // State variables the program may read.
  std::size_t nodeCount = 0;           // Nodes of the genome it came from.

  bool hasCalls() const;  // Whether some instruction is a call (expr::isCall).
};

// Lowers `genome` for states of `inputDim` variables. Throws LowerError when the genome is
// malformed, reads a variable >= inputDim, or breaks a kMaxLower* limit.
Program lower(const expr::Genome& genome, std::size_t inputDim);

// Runs a program on one state: features[k] = value of output k. `scratch` must hold
// program.code.size() doubles.
void run(const Program& program, const double* state, double* features, double* scratch);

}  // namespace gpfd::jit
