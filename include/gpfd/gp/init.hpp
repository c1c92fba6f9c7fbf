// gp: random trees and genomes (ramped half-and-half, Koza 1992), within the search space's
// limits.
#pragma once

#include "gpfd/gp/search_space.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::gp {

// A terminal drawn uniformly from: the variables, the fixed constants, and (if enabled) one
// slot for a new ephemeral random constant.
expr::Node randomTerminal(Rng& rng, const SearchSpace& space);
// A function drawn uniformly from the primitive set's functions of the given arity (-1: any).
expr::Node randomFunction(Rng& rng, const SearchSpace& space, int arity = -1);

// A random tree of at most `depth` levels: "full" puts functions on every level above the last;
// "grow" picks terminals or functions at random (a terminal with probability t / (t + f)).
expr::Tree randomTree(Rng& rng, const SearchSpace& space, int depth, bool full);

// One genome by ramped half-and-half; every feature within the limits.
expr::Genome randomGenome(Rng& rng, const SearchSpace& space);

}  // namespace gpfd::gp
