// `gpfd reproduce`: the paper's experiments, figures and report in one command.
#include <fmt/format.h>

#include "command.hpp"
#include "gpfd/experiments/reproduce.hpp"
#include "gpfd/jit/x86_compiler.hpp"
#include "gpfd/service/resources.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/version.hpp"
#include "interrupt.hpp"

namespace gpfd::app {
namespace {

struct ReproduceCli {
  std::vector<std::string> figures{"all"};
  std::string scale = "quick";
  std::uint64_t seed = 1;
  std::string out = "results/reproduce";
  int threads = 0;
  bool quiet = false;
  bool skipFourier = false;
  int gpRuns = 1;
  std::vector<std::string> sets;
  std::string baseline;
};

int reproduceCommand(const ReproduceCli& c) {
  experiments::ReproduceOptions o;
  o.paperScale = c.scale == "paper";
  o.seed = c.seed;
  o.outDir = c.out;
  o.threads = service::usableThreads(c.threads);
  o.version = kVersion;
  o.revision = kRevision;
  o.quiet = c.quiet;
  o.skipFourier = c.skipFourier;
  o.gpRuns = c.gpRuns;
  o.overrides = c.sets;
  o.baselineDir = c.baseline;
  std::vector<std::string> figures;
  for (const auto& f : c.figures) {
    if (f == "all") {
      for (const auto& figure : experiments::kFigures) {
        // Figure 3 measures the JIT: a build without it leaves it out.
        if (figure != "fig3" || jit::jitAvailable()) figures.push_back(figure);
      }
    } else {
      figures.push_back(f);
    }
  }
  o.stop = &stopOnInterrupt(
      "\ngpfd reproduce: stopping at the next checkpoint; press Ctrl-C again to stop at once "
      "(a rerun continues from what is saved)\n");
  experiments::reproduce(figures, o);
  return 0;
}

const CommandRegistration registration{
    "reproduce", [](CLI::App& app) {
      auto* cmd = app.add_subcommand(
          "reproduce",
          "Regenerate the paper's experiments, figures and report (fig1 fig3 fig5 fig6 "
          "fig7, or all); reruns continue where a previous run stopped");
      auto c = std::make_shared<ReproduceCli>();
      cmd->add_option("figures", c->figures, "fig1, fig3, fig5, fig6, fig7 or all")
          ->capture_default_str();
      cmd->add_option("--scale", c->scale, "quick (minutes) or paper (the paper's settings)")
          ->check(oneOf({"quick", "paper"}))
          ->capture_default_str();
      cmd->add_option("--seed", c->seed, "Random seed")->capture_default_str()->check(seedValue());
      cmd->add_option("--out", c->out, "Output directory")->capture_default_str();
      cmd->add_option("--threads", c->threads, "Worker threads (0: all cores)")
          ->check(threadCount());
      cmd->add_flag("--quiet", c->quiet, "No progress output");
      cmd->add_flag("--skip-fourier", c->skipFourier,
                    "Leave out the Fourier-basis assessments (a later run adds them)");
      cmd->add_option("--gp-runs", c->gpRuns,
                      "Independent GP runs per benchmark (1-100), each assessed against the "
                      "original variables; the report gives the method-level verdict")
          ->check(bounded(1, 100))
          ->capture_default_str();
      cmd->add_option("--set", c->sets,
                      "Override a key of every benchmark's config: --set validation.candidates=0")
          ->allow_extra_args(false);
      cmd->add_option("--baseline", c->baseline,
                      "An earlier reproduction's output directory to compare the method-level "
                      "results with")
          ->check(CLI::ExistingDirectory);
      return [c] { return reproduceCommand(*c); };
    }};

}  // namespace
}  // namespace gpfd::app
