// `gpfd bench jit`: the paper's Figure 3 (experiments/bench_jit.hpp does the work).
#include "command.hpp"
#include "gpfd/experiments/bench_jit.hpp"

namespace gpfd::app {
namespace {

using experiments::BenchJitArgs;

const CommandRegistration registration{
    "bench", [](CLI::App& app) -> std::function<int()> {
      auto* bench = app.add_subcommand("bench", "Benchmarks of gpfd's components");
      bench->require_subcommand(1);
      auto args = std::make_shared<BenchJitArgs>();
      auto* jitCmd = bench->add_subcommand(
          "jit",
          "Figure 3: feature-function speed of tree interpreter, interpreter, JIT, AOT, batch");
      jitCmd->add_option("--depths", args->depths, "Tree depths, e.g. 2-8")->capture_default_str();
      jitCmd->add_option("--calls", args->calls, "Calls per function and method")
          ->capture_default_str()
          ->check(bounded(1, 1000000000));
      jitCmd->add_option("--runs", args->runs, "Random functions per depth, averaged")
          ->capture_default_str()
          ->check(bounded(1, 1000));
      jitCmd->add_option("--seed", args->seed, "Seed; the default has AOT reference code")
          ->capture_default_str()
          ->check(seedValue());
      jitCmd->add_option("--out", args->out, "Output directory")->capture_default_str();
      jitCmd
          ->add_option("--memory-cycles", args->memoryCycles,
                       "Compile/release cycles of the resident-memory check (0: skip)")
          ->capture_default_str()
          ->check(bounded(0, 100000000));
      return [args, jitCmd]() {
        if (!jitCmd->parsed()) return 2;
        experiments::runBenchJit(*args);
        return 0;
      };
    }};

}  // namespace
}  // namespace gpfd::app
