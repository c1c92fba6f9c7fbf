// Compile-time phases of the JIT on the Figure 3 functions (arithmetic set, depth = argument):
// lowering alone, lowering + scalar code, lowering + AVX2 batch code. `gpfd bench jit` reports
// the end-to-end figure; this splits it.
#include <benchmark/benchmark.h>

#include "gpfd/experiments/bench_functions.hpp"
#include "gpfd/jit/program.hpp"
#include "gpfd/jit/x86_compiler.hpp"

namespace {

using namespace gpfd;

expr::Genome figure3Genome(int depth) {
  return expr::Genome::fromFeatures({experiments::benchTree(
      experiments::kBenchDefaultSeed, experiments::BenchSet::Arithmetic, depth, 0)});
}

void BM_Lower(benchmark::State& state) {
  const auto genome = figure3Genome(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(jit::lower(genome, experiments::kBenchVariables));
  state.counters["nodes"] = static_cast<double>(genome.size());
}

void BM_CompileScalar(benchmark::State& state) {
  const auto genome = figure3Genome(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const auto code = jit::compileScalar(jit::lower(genome, experiments::kBenchVariables));
    benchmark::DoNotOptimize(code.entry());
  }
  state.counters["nodes"] = static_cast<double>(genome.size());
}

void BM_CompileBatch(benchmark::State& state) {
  if (!jit::hostHasAvx2()) {
    state.SkipWithError("no AVX2");
    return;
  }
  const auto genome = figure3Genome(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const auto code = jit::compileBatch(jit::lower(genome, experiments::kBenchVariables));
    benchmark::DoNotOptimize(code.entry());
  }
}

BENCHMARK(BM_Lower)->DenseRange(2, 8, 2);
BENCHMARK(BM_CompileScalar)->DenseRange(2, 8, 2);
BENCHMARK(BM_CompileBatch)->DenseRange(2, 8, 2);

}  // namespace

BENCHMARK_MAIN();
