// experiments: the measurements behind `gpfd bench jit`, the paper's Figure 3 reproduced and
// extended (Girgin & Preux, section 3.3: complete trees of depth 2..8, each run 1,000,000 times,
// averaged over 10 runs). For each operator set, depth and run it times the reference tree walker,
// the fast interpreter, the JIT, the AOT reference (when given) and the AVX2 batch kernel, after
// checking that all of them agree bit for bit. Times are CPU time of the measuring thread.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gpfd/experiments/bench_functions.hpp"
#include "gpfd/jit/x86_compiler.hpp"

namespace gpfd::experiments {

struct Figure3Options {
  int minDepth = 2;
  int maxDepth = 8;
  std::size_t calls = 1000000;  // Calls per function and method (states, for batch).
  int runs = 10;                // Independent random functions per depth, averaged.
  std::uint64_t seed = kBenchDefaultSeed;
};

struct Figure3Row {
  BenchSet set;
  int depth;
  double nodes;        // Mean node count of the functions.
  std::string method;  // tree, interp, jit, aot or batch.
  double nsPerCall;    // Mean over runs; per state for batch.
  double compileUs;    // jit only (lower + compile + release, mean); NaN otherwise.
};

// The AOT reference function of (set, depth, run), or nullptr when there is none.
using AotLookup = std::function<jit::ScalarFunction(BenchSet, int depth, int run)>;

// Rows ordered by set, depth, method. The aot rows appear for a depth only when every run has a
// reference function. Throws std::runtime_error when any two methods disagree on some state, and
// CompileError when the JIT is unavailable.
std::vector<Figure3Row> runFigure3(const Figure3Options& options, const AotLookup& aot);

// Resident set size (KiB) before and after `cycles` compile/release cycles of a CompiledFeatureMap
// (scalar and batch code) for a depth-6 Figure 3 function, after a warm-up of 1,000 cycles.
struct MemoryCheck {
  std::size_t cycles = 0;
  long rssBeforeKiB = 0;
  long rssAfterKiB = 0;
};
MemoryCheck measureCompileReleaseMemory(std::size_t cycles, std::uint64_t seed);

}  // namespace gpfd::experiments
