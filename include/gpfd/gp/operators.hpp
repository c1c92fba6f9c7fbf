// gp: the paper's five variation operators (Table 1 and the feature-list crossover of Figure 2).
// Every operator returns offspring within the search space's limits; when a random choice would
// break a limit it retries, and after kMaxAttempts it returns the parents unchanged.
#pragma once

#include <utility>

#include "gpfd/gp/search_space.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::gp {

inline constexpr int kMaxAttempts = 16;

// Probability of choosing an operator (internal) node rather than a terminal as a crossover or
// mutation point, when the feature has one (Koza's 90/10 rule).
inline constexpr double kInternalNodeBias = 0.9;

using Offspring = std::pair<expr::Genome, expr::Genome>;

// A node and its branch in one feature of `a` swapped with a node and branch of `b`.
Offspring subtreeCrossover(Rng& rng, const expr::Genome& a, const expr::Genome& b,
                           const SearchSpace& space);
// Feature-list crossover: cut points 0 < i < n and 0 < j < m; children a[0, i) + b[j, m) and
// b[0, j) + a[i, n). Needs n, m >= 2.
Offspring featureListCrossover(Rng& rng, const expr::Genome& a, const expr::Genome& b,
                               const SearchSpace& space);
// One node replaced by a different one of the same arity (a terminal by another terminal).
expr::Genome nodeMutation(Rng& rng, const expr::Genome& g, const SearchSpace& space);
// One node replaced by a random subtree of depth <= space.mutationDepth (grow method).
expr::Genome treeMutation(Rng& rng, const expr::Genome& g, const SearchSpace& space);
// One operator node replaced by one of its children.
expr::Genome shrinkage(Rng& rng, const expr::Genome& g, const SearchSpace& space);

}  // namespace gpfd::gp
