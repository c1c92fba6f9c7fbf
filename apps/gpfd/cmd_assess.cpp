// `gpfd assess`: the paper's test protocol for feature sets (long training, N runs, statistics).
#include <fmt/format.h>

#include <filesystem>

#include "command.hpp"
#include "config_loading.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/assessment.hpp"
#include "gpfd/util/directory_lock.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"
#include "listings.hpp"
#include "param_routing.hpp"

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
  std::string out;
  bool force = false;
  bool quiet = false;
};

// The budget of one assessment run (policy updates, iterations: the learner's budget parameter).
long long runBudget(const run::ExperimentConfig& config) {
  const auto& learner = rl::LearnerRegistry::global().info(config.learner);
  auto params = config.learnerParams;
  for (const auto& [k, v] : config.assessParams) params[k] = v;
  if (const auto given = params.find(learner.budgetParam); given != params.end()) {
    return parseInteger(given->second, learner.name + "." + learner.budgetParam);
  }
  for (const auto& spec : learner.params) {
    if (spec.name == learner.budgetParam) {
      return parseInteger(spec.defaultValue, learner.name + "." + learner.budgetParam);
    }
  }
  return 0;
}

// The results directory: --out (refused when it holds an assessment, unless --force), or a fresh
// results/assess-ENV (-2, -3, ... when taken), locked against other writers.
DirectoryLock outputDirectory(const AssessOptions& o, const std::string& env) {
  if (o.out.empty()) return DirectoryLock::lockFresh("results/assess-" + env);
  DirectoryLock lock(o.out);
  if (!o.force && std::filesystem::exists(o.out + "/summary.csv")) {
    throw InputError(
        "the directory already holds an assessment; pass --force to replace it, or choose "
        "another --out",
        o.out);
  }
  return lock;
}

run::ExperimentConfig assessConfig(const AssessOptions& o) {
  run::ExperimentConfig config;
  if (!o.config.empty()) {
    config = loadConfig(o.config, {});
    if (!o.env.empty() && o.env != config.env) {
      throw InputError("the environment differs from the config's (" + config.env + ")", o.env);
    }
  } else {
    if (o.env.empty()) throw InputError("give an environment or --config", "gpfd assess");
    config.env = o.env;
    config.learner = env::Registry::global().info(o.env).defaultLearner;
  }
  const auto routed = routeParams(o.params, env::Registry::global().info(config.env), "--param");
  for (const auto& [key, value] : routed.env) config.envParams[key] = value;
  for (const auto& [key, value] : routed.learner) config.assessParams[key] = value;
  if (o.budget > 0) {
    const auto& learner = rl::LearnerRegistry::global().info(config.learner);
    config.assessParams[learner.budgetParam] = std::to_string(o.budget);
  }
  if (o.runs > 0) config.assessRuns = o.runs;
  config.seed = o.seed;
  run::validate(config);
  return config;
}

int assess(const AssessOptions& o) {
  const auto config = assessConfig(o);
  const run::LearningTask task(config, run::LearningTask::Budget::Assessment);
  const std::size_t dim = task.stateDim();
  const auto raw = std::make_shared<const features::RawFeatureMap>(dim);

  // Every input is read and checked before anything is written.
  std::vector<run::FeatureSet> sets;
  if (o.raw || !o.features.empty()) sets.push_back({"original", raw});
  for (const auto& path : o.features) {
    const auto file = expr::readFeaturesFile(path, task.stateNames(), config.env);
    std::string name = std::filesystem::path(path).stem().string();
    for (const auto& s : sets) {
      if (s.name == name) name += "-" + std::to_string(sets.size());
    }
    // Assessed as GP evaluated them: with the original variables appended when the config's
    // fitness.with_original says so; --with-original adds that variant as a further set.
    const bool asEvolved = config.withOriginal;
    sets.push_back({name + (asEvolved ? "+original" : ""),
                    run::genomeFeatureMap(file.genome, dim, asEvolved)});
    if (o.withOriginal && !asEvolved) {
      sets.push_back({name + "+original", run::genomeFeatureMap(file.genome, dim, true)});
    }
  }
  if (o.fourier > 0) sets.push_back(run::fourierFeatureSet(task, o.fourier));
  if (sets.empty())
    throw InputError("nothing to assess: give --features FILE... or --raw", "gpfd assess");
  // Every run's curve is kept until the statistics are computed.
  requireMemory(static_cast<double>(sets.size()) * config.assessRuns *
                    static_cast<double>(runBudget(config) + 1) * sizeof(rl::CurvePoint),
                "the learning curves of every run", "--runs, --budget");
  const DirectoryLock lock = outputDirectory(o, config.env);
  const std::string& out = lock.directory();

  if (!o.quiet) {
    fmt::print("gpfd assess: {} feature sets x {} runs on {} ({}), seed {}\n", sets.size(),
               config.assessRuns, config.env, config.learner, config.seed);
    std::fflush(stdout);
  }
  const auto result =
      run::runAssessment(task, sets, config.assessRuns, config.seed, threads(o.threads));
  const auto summary = run::summarizeAssessment(result, 0);
  run::writeAssessment(out, result, summary, config.env + ": " + config.learner,
                       rl::LearnerRegistry::global().info(config.learner).rowName);
  int diverged = 0;
  for (const auto& row : summary) diverged += row.diverged;
  if (!o.quiet) {
    for (const auto& row : summary) {
      fmt::print(
          "{:<24} final {:.6g} ± {:.3g} (Welch p {:.3g}, Mann-Whitney p {:.3g}, d {:.3g})  area "
          "{:.6g} (Welch p {:.3g})\n",
          row.name, row.final.mean, row.final.halfWidth, row.vsBaseline.welchP,
          row.vsBaseline.mannWhitneyP, row.vsBaseline.cohenD, row.area.mean,
          row.areaVsBaseline.welchP);
    }
    fmt::print("results in {}\n", out);
  }
  if (diverged > 0) {
    throw NumericalError(fmt::format("{} of {} runs diverged (non-finite states, features or "
                                     "weights); summary.csv counts them per set",
                                     diverged, sets.size() * config.assessRuns),
                         out);
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
                      "taken)");
      cmd->add_flag("--force", o->force, "Replace the assessment already in --out");
      cmd->add_flag("--quiet", o->quiet, "Print nothing");
      return [o] { return assess(*o); };
    }};

}  // namespace
}  // namespace gpfd::app
