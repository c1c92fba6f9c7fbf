// `gpfd assess`: the paper's test protocol for feature sets (long training, N runs, statistics).
// The command only turns its flags into a service::AssessRequest (gpfd/service/assess.hpp).
#include <fmt/format.h>

#include <cstdio>
#include <optional>

#include "command.hpp"
#include "gpfd/service/assess.hpp"
#include "gpfd/util/error.hpp"
#include "listings.hpp"

namespace gpfd::app {
namespace {

struct AssessOptions {
  std::string env;
  std::string config;
  std::vector<std::string> features;
  bool raw = false;
  bool withOriginal = false;
  int fourier = 0;  // Order of a Fourier basis set to add; 0: none.
  int runs = 0;
  int budget = 0;
  std::vector<std::string> params;
  std::uint64_t seed = 1;
  int threads = 0;
  std::optional<std::string> out;
  bool force = false;
  bool quiet = false;
};

void print(const std::string& text) {
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
}

int assess(const AssessOptions& o) {
  service::AssessRequest request;
  request.env = o.env;
  request.config = o.config;
  for (const auto& path : o.features)
    request.features.push_back({.name = {}, .path = path, .file = {}});
  request.raw = o.raw;
  request.withOriginal = o.withOriginal;
  request.fourier = o.fourier;
  request.runs = o.runs;
  request.budget = o.budget;
  request.params = o.params;
  request.seed = o.seed;
  request.threads = o.threads;
  request.out = {o.out, o.force, "--out"};
  const auto result = service::assess(request, o.quiet ? service::TextSink{} : print);
  if (result.diverged > 0) {
    throw NumericalError(fmt::format("{} of {} runs diverged (non-finite states, features or "
                                     "weights); summary.csv counts them per set",
                                     result.diverged, result.runs),
                         result.dir);
  }
  return 0;
}

const CommandRegistration registration{
    "assess", [](CLI::App& app) {
      auto* cmd = app.add_subcommand(
          "assess",
          "Train feature sets with the long budget over N runs and test them against the "
          "original state variables");
      auto o = std::make_shared<AssessOptions>();
      cmd->add_option("env", o->env, "Environment (see gpfd envs); optional with --config")
          ->check(environmentName());
      cmd->add_option("--config", o->config,
                      "Experiment config (file or shipped name) for the learner");
      cmd->add_option("--features", o->features, "Features files to assess")->expected(1, -1);
      cmd->add_flag("--raw", o->raw, "Assess the original state variables (always the baseline)");
      cmd->add_flag("--with-original", o->withOriginal,
                    "Also assess each file's features + the original variables");
      cmd->add_option(
             "--fourier", o->fourier,
             "Also assess the Fourier basis of this order (Konidaris et al. 2011; 3 in the "
             "report); full coupling up to 1024 terms, else independent")
          ->check(bounded(1, 9));
      cmd->add_option("--runs", o->runs, "Independent runs per set (default: the config's, 20)")
          ->check(bounded(1, kMaxRuns));
      cmd->add_option("--budget", o->budget,
                      "The learner's budget per run: sets its budget parameter (gpfd learners)")
          ->check(bounded(1, kMaxBudget));
      cmd->add_option("--param", o->params, "k=v for the environment or the learner (repeatable)");
      cmd->footer(
          "Learner parameters (defaults, ranges and meanings: gpfd learners; the "
          "environments': gpfd envs):\n" +
          learnerParamSummary());
      cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str()->check(seedValue());
      cmd->add_option("--threads", o->threads, "Worker threads (0: all cores)")
          ->check(threadCount());
      cmd->add_option("--out", o->out,
                      "Output directory (default results/assess-ENV, or results/assess-ENV-N when "
                      "taken); one that already holds files needs --force");
      cmd->add_flag("--force", o->force,
                    "Write into an --out that already holds files (replacing an assessment there)");
      cmd->add_flag("--quiet", o->quiet, "Print nothing");
      return [o] { return assess(*o); };
    }};

}  // namespace
}  // namespace gpfd::app
