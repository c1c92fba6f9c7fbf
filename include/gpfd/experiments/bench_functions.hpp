// experiments: the random functions of the paper's Figure 3 (Girgin & Preux, section 3.3): complete
// trees of a given depth over 4 state variables, for `gpfd bench jit` and for the ahead-of-time
// reference code generated from them at build time (tools/aot). Both sides call these functions,
// so the trees are identical for the same seed.
#pragma once

#include <cstdint>
#include <string_view>

#include "gpfd/expr/genome.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::experiments {

enum class BenchSet : int {
  Arithmetic = 0,  // {+, -, *, /}: complete binary trees, 2^d - 1 nodes.
  Unary = 1,       // {+, -, *, /, sin, cos, sqrt}: a unary node has one child of depth d - 1.
};
inline constexpr int kBenchSetCount = 2;
inline constexpr int kBenchVariables = 4;
// The seed the ahead-of-time reference functions were generated with; `gpfd bench jit` uses it
// by default.
inline constexpr std::uint64_t kBenchDefaultSeed = 2010;
// The AOT reference covers these depths and runs (see cmake/jit_aot.cmake).
inline constexpr int kAotMinDepth = 2;
inline constexpr int kAotMaxDepth = 8;
inline constexpr int kAotRuns = 10;

std::string_view benchSetName(BenchSet set);  // "arithmetic" or "unary".

// The function of run `run` at `depth` levels: every path from the root has `depth` nodes;
// terminals are the variables x0..x3 and the paper's constants {1, 2, e ~ U[0, 1)}. The tree is a
// pure function of (seed, set, depth, run).
expr::Tree benchTree(std::uint64_t seed, BenchSet set, int depth, int run);

}  // namespace gpfd::experiments
