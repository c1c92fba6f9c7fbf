// The evolution tests' search space: the control primitives over two variables, small genomes.
#pragma once

#include "gpfd/gp/search_space.hpp"

namespace gpfd::gp::fixtures {

inline SearchSpace smallSpace() {
  SearchSpace s;
  s.primitives = expr::PrimitiveSet::named("control");
  s.variableCount = 2;
  s.limits = {1, 5, 6, 30};
  return s;
}

}  // namespace gpfd::gp::fixtures
