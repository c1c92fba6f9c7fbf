// expr: primitive sets, i.e. the functions and terminals that feature functions are built from,
// selected by name in configs.
#pragma once

#include <string>
#include <vector>

#include "gpfd/expr/ops.hpp"

namespace gpfd::expr {

// The functions GP may use, and the terminals: the problem's state variables, the fixed
// constants, and (when `ephemeral`) ephemeral random constants drawn uniformly from
// [ephemeralLow, ephemeralHigh] when a node is created and fixed after (the paper: {1, 2, e},
// e in [0, 1]).
struct PrimitiveSet {
  std::string name;
  std::vector<Op> functions;
  std::vector<double> constants{1.0, 2.0};
  bool ephemeral = true;
  double ephemeralLow = 0.0;
  double ephemeralHigh = 1.0;

  // "control" = {+, -, *, /, sin, cos, sqrt} (Acrobot, swimmer, cart-pole);
  // "tetris" = {+, -, *, /, min, max, absdiff}; "arithmetic" = {+, -, *, /};
  // "all" = every operator; or a comma-separated list of operator names/symbols
  // ("add,mul,sin" or "+,*,sin"). Throws InputError naming an unknown set or operator.
  static PrimitiveSet named(const std::string& spec);

  bool contains(Op op) const;
  // The functions of the given arity.
  std::vector<Op> functionsOfArity(int arity) const;
};

}  // namespace gpfd::expr
