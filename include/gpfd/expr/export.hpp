// expr: discovered features as code a user can paste into their own agent: a C function, a NumPy
// function, or LaTeX. The C and NumPy code reproduce the protected semantics of ops.hpp exactly
// (saturation, protected division, sqrt and log), so they compute the same values as gpfd.
#pragma once

#include <string>

#include "gpfd/expr/genome.hpp"
#include "gpfd/expr/print.hpp"

namespace gpfd::expr {

// `void gpfd_features(const double* s, double* f)`, f[k] = feature k; self-contained C99.
std::string exportC(const Genome& genome, const VariableNames& names);
// `def features(s)`: s[..., i] is variable i (works on one state or a batch); returns one float64
// array of shape s.shape[:-1] + (k,), feature k in [..., k]. Needs NumPy.
std::string exportPython(const Genome& genome, const VariableNames& names);
// One `\phi_k(s) = ...` line per feature, in an align* environment.
std::string exportLatex(const Genome& genome, const VariableNames& names);
// The features in `format`: "infix" or "sexpr" (one feature per line), or one of the exports above
// ("c", "python", "latex"). InputError for another format.
std::string exportAs(const Genome& genome, const VariableNames& names, const std::string& format);

}  // namespace gpfd::expr
