// `gpfd bench jit`, also run by `gpfd reproduce fig3` (the ahead-of-time reference functions it
// compares with are linked into the tool only).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "gpfd/experiments/bench_functions.hpp"

namespace gpfd::experiments {

struct BenchJitArgs {
  std::string depths = "2-8";
  std::size_t calls = 1000000;
  int runs = 10;
  std::uint64_t seed = kBenchDefaultSeed;
  std::string out = "bench-jit";
  std::size_t memoryCycles = 100000;
  bool print = true;  // Print the summary (it is written to OUT/jit_summary.txt either way).
};

// Runs the benchmark and writes OUT/jit.csv, jit_unary.csv, jit.png, jit.svg and jit_summary.txt.
// InputError for bad arguments or an unwritable OUT.
void runBenchJit(const BenchJitArgs& args);

}  // namespace gpfd::experiments
