#include "gpfd/experiments/figure3.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "gpfd/expr/eval.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/jit/fast_interpreter.hpp"

namespace gpfd::experiments {
using namespace gpfd::jit;  // The JIT's names, used throughout.
namespace {

constexpr std::size_t kStates = 1024;  // Varying states, cycled through.
constexpr int kCompileRepeats = 1000;

// All times are CPU time of the measuring thread, so that other processes sharing the cores do
// not inflate them (the machine this was written on has 2 cores shared by several users).
struct Clock {
  static double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e9 + static_cast<double>(t.tv_nsec);
  }
};

double elapsedNs(double start) { return Clock::now() - start; }

volatile double gSink = 0.0;  // Keeps the timed results observable.

// Mean ns per call of f(state, out) over `calls` calls cycling through the states.
template <typename F>
double nsPerCall(std::size_t calls, const std::vector<double>& states, F&& f) {
  std::vector<double> out(kStates);
  for (std::size_t i = 0; i < std::min<std::size_t>(calls, 10000); ++i) {  // Warm-up.
    const std::size_t j = i & (kStates - 1);
    f(states.data() + j * kBenchVariables, &out[j]);
  }
  const auto start = Clock::now();
  for (std::size_t i = 0; i < calls; ++i) {
    const std::size_t j = i & (kStates - 1);
    f(states.data() + j * kBenchVariables, &out[j]);
  }
  const double ns = elapsedNs(start);
  double sum = 0.0;
  for (double x : out) sum += x;
  gSink = gSink + sum;
  return ns / static_cast<double>(calls);
}

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

long residentKiB() {
  long pages = 0, resident = 0;
  std::ifstream statm("/proc/self/statm");
  if (!(statm >> pages >> resident)) resident = 0;
  return resident * 4;
}

struct Accumulator {
  double sum = 0.0;
  int count = 0;
  void add(double x) {
    sum += x;
    ++count;
  }
  double mean() const { return count ? sum / count : std::numeric_limits<double>::quiet_NaN(); }
};

}  // namespace

std::vector<Figure3Row> runFigure3(const Figure3Options& options, const AotLookup& aot) {
  if (!jitAvailable()) throw CompileError("this build has no JIT");
  std::vector<Figure3Row> rows;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int s = 0; s < kBenchSetCount; ++s) {
    const auto set = static_cast<BenchSet>(s);
    for (int depth = options.minDepth; depth <= options.maxDepth; ++depth) {
      Accumulator nodes, tree, interp, jit, aotTime, batch, compile;
      bool aotComplete = true;
      for (int run = 0; run < options.runs; ++run) {
        const expr::Tree function = benchTree(options.seed, set, depth, run);
        const expr::Genome genome = expr::Genome::fromFeatures({function});
        Rng rng(deriveSeed(options.seed, 99, s, depth, run));
        std::vector<double> states(kStates * kBenchVariables);
        for (double& x : states) x = rng.uniform(-2.0, 2.0);

        const FastInterpretedFeatureMap fast(genome, kBenchVariables);
        const NativeCode code = compileScalar(fast.program());
        const auto native = reinterpret_cast<ScalarFunction>(code.entry());
        const CompiledFeatureMap compiled(genome, kBenchVariables);
        const ScalarFunction reference = aot ? aot(set, depth, run) : nullptr;
        aotComplete = aotComplete && reference != nullptr;

        // Every method must agree with the reference interpreter before anything is timed.
        std::vector<double> batchOut(kStates);
        compiled.evaluateBatch(states.data(), kStates, batchOut.data());
        for (std::size_t i = 0; i < kStates; ++i) {
          const double* x = states.data() + i * kBenchVariables;
          const double expected = expr::evaluate(function, x);
          double viaFast = 0, viaJit = 0, viaAot = expected;
          fast.evaluate(x, &viaFast);
          native(x, &viaJit);
          if (reference) reference(x, &viaAot);
          if (!sameBits(expected, viaFast) || !sameBits(expected, viaJit) ||
              !sameBits(expected, viaAot) || !sameBits(expected, batchOut[i])) {
            throw std::runtime_error("bench jit: methods disagree on " +
                                     std::string(benchSetName(set)) + " depth " +
                                     std::to_string(depth) + " run " + std::to_string(run));
          }
        }

        nodes.add(static_cast<double>(function.size()));
        tree.add(nsPerCall(options.calls, states, [&](const double* x, double* out) {
          *out = expr::evaluate(function, x);
        }));
        interp.add(nsPerCall(options.calls, states,
                             [&](const double* x, double* out) { fast.evaluate(x, out); }));
        jit.add(nsPerCall(options.calls, states, native));
        if (reference) aotTime.add(nsPerCall(options.calls, states, reference));
        {
          const std::size_t rounds = std::max<std::size_t>(1, options.calls / kStates);
          const auto start = Clock::now();
          for (std::size_t r = 0; r < rounds; ++r) {
            compiled.evaluateBatch(states.data(), kStates, batchOut.data());
          }
          batch.add(elapsedNs(start) / static_cast<double>(rounds * kStates));
          gSink = gSink + batchOut[0];
        }
        {
          const auto start = Clock::now();
          for (int r = 0; r < kCompileRepeats; ++r) {
            const NativeCode fresh = compileScalar(lower(genome, kBenchVariables));
            if (!fresh) throw CompileError("empty code");
          }
          compile.add(elapsedNs(start) / kCompileRepeats / 1000.0);
        }
      }
      auto row = [&](const char* method, double ns, double us) {
        rows.push_back({set, depth, nodes.mean(), method, ns, us});
      };
      row("tree", tree.mean(), nan);
      row("interp", interp.mean(), nan);
      row("jit", jit.mean(), compile.mean());
      if (aotComplete && aot) row("aot", aotTime.mean(), nan);
      row("batch", batch.mean(), nan);
    }
  }
  return rows;
}

MemoryCheck measureCompileReleaseMemory(std::size_t cycles, std::uint64_t seed) {
  const expr::Genome genome = expr::Genome::fromFeatures(
      {benchTree(seed, BenchSet::Unary, 6, 0), benchTree(seed, BenchSet::Arithmetic, 6, 0)});
  auto cycle = [&] {
    const CompiledFeatureMap map(genome, kBenchVariables);
    if (!map.isNative()) throw CompileError(map.fallbackReason());
  };
  for (int i = 0; i < 1000; ++i) cycle();
  MemoryCheck check;
  check.cycles = cycles;
  check.rssBeforeKiB = residentKiB();
  for (std::size_t i = 0; i < cycles; ++i) cycle();
  check.rssAfterKiB = residentKiB();
  return check;
}

}  // namespace gpfd::experiments
