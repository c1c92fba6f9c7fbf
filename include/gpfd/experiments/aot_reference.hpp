// experiments: ahead-of-time compiled C++ of the Figure 3 functions (bench_functions.hpp) for the
// default seed, generated at build time by tools/aot/gen_aot and compiled with the project's normal
// flags: the ceiling for per-call code in `gpfd bench jit`. Defined in the generated library
// gpfd_jit_aot, which only the gpfd executable links.
#pragma once

#include <cstdint>
#include <span>

#include "gpfd/experiments/bench_functions.hpp"
#include "gpfd/jit/x86_compiler.hpp"

namespace gpfd::experiments {

struct AotFunction {
  BenchSet set;
  int depth;
  int run;
  jit::ScalarFunction function;  // features[0] = the tree's value on state[0..4).
};

// Every generated function; generated for seed aotSeed().
std::span<const AotFunction> aotFunctions();
std::uint64_t aotSeed();

}  // namespace gpfd::experiments
