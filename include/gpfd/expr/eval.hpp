// expr: the reference interpreter, a plain tree walk over the prefix array under the protected
// semantics of ops.hpp. Every other evaluator (fast interpreter, JIT, exporters) must agree with
// it bit for bit.
#pragma once

#include "gpfd/expr/genome.hpp"

namespace gpfd::expr {

// Value of a well-formed tree on `state` (which must hold every variable the tree reads).
double evaluate(TreeView tree, const double* state);
// All features of a genome: features[k] = value of feature k.
void evaluate(const Genome& genome, const double* state, double* features);

}  // namespace gpfd::expr
