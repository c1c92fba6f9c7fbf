// Shared by the expr tests: random genomes over every operator and random or edge states.
#pragma once

#include <limits>
#include <vector>

#include "gpfd/gp/init.hpp"

namespace gpfd::expr::testing {

inline gp::SearchSpace everyOperator(int variables, int maxDepth = 7) {
  gp::SearchSpace space;
  space.primitives = PrimitiveSet::named("all");
  space.primitives.ephemeralLow = -3.0;  // Negative constants exercise the printer's signs.
  space.primitives.ephemeralHigh = 3.0;
  space.variableCount = variables;
  space.limits = {1, 6, maxDepth, 200};
  space.initMinDepth = 1;
  space.initMaxDepth = maxDepth;
  space.initMaxFeatures = 6;
  return space;
}

// Edge values a state variable may take, non-finite ones included.
inline std::vector<double> edgeValues() {
  const double inf = std::numeric_limits<double>::infinity();
  return {0.0,
          -0.0,
          1e-320,
          -1e-320,
          1e-11,
          1.0,
          -1.0,
          0.5,
          1e308,
          -1e308,
          inf,
          -inf,
          std::numeric_limits<double>::quiet_NaN(),
          710.0,
          3.5};
}

// A random state: mostly ordinary values, sometimes edge values.
inline std::vector<double> randomState(Rng& rng, int variables) {
  static const auto edges = edgeValues();
  std::vector<double> state(variables);
  for (auto& v : state) {
    v = rng.bernoulli(0.2) ? edges[rng.below(edges.size())] : rng.uniform(-5.0, 5.0);
  }
  return state;
}

}  // namespace gpfd::expr::testing
