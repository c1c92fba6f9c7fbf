// gp: what GP may build: the primitive set, the problem's variable count and the genome limits,
// with the initialisation settings.
#pragma once

#include "gpfd/expr/genome.hpp"
#include "gpfd/expr/primitive_set.hpp"

namespace gpfd::gp {

struct SearchSpace {
  expr::PrimitiveSet primitives = expr::PrimitiveSet::named("control");
  int variableCount = 1;
  expr::GenomeLimits limits;
  // Ramped half-and-half initialisation: tree depths ramp over [initMinDepth, initMaxDepth]
  // (clamped to limits.maxDepth); feature counts are uniform in [limits.minFeatures,
  // initMaxFeatures] (clamped to limits.maxFeatures).
  int initMinDepth = 2;
  int initMaxDepth = 4;
  int initMaxFeatures = 4;
  // Tree mutation grows a random subtree of depth at most this (the paper: 3).
  int mutationDepth = 3;
};

}  // namespace gpfd::gp
