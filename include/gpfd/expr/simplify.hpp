// expr: algebraic simplification for display, export and canonical keys. Value-preserving under
// the protected semantics of ops.hpp (which keep every value finite): constant folding, x - x = 0,
// x / x = 1, x * 1 = x, x * 0 = 0, x + 0 = x, x - 0 = x, x / 1 = x, neg(neg(x)) = x,
// abs(abs(x)) = abs(x), min(x, x) = max(x, x) = x, absdiff(x, x) = 0. Values compare equal
// (== on doubles, so 0 and -0 count as one value).
#pragma once

#include "gpfd/expr/genome.hpp"

namespace gpfd::expr {

Tree simplify(TreeView tree);
Genome simplify(const Genome& genome);

}  // namespace gpfd::expr
