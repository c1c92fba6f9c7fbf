// python: discovery (`gpfd evolve`), GP's fitness of one feature set, and assessment
// (`gpfd assess`) from Python, through the same library calls and config loading as the command
// line. gpfd.discovery wraps them.
#include <fmt/format.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>

#include "bindings.hpp"
#include "config_loading.hpp"
#include "feature_set.hpp"
#include "genome_blob.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/assessment.hpp"
#include "gpfd/run/discovery.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/version.hpp"
#include "param_routing.hpp"

namespace gpfd::python {
namespace {

// Fitness evaluation by a Python callable, evaluate(config_text, [(genome bytes, seed), ...]) ->
// [fitness, ...], which runs run::trialFitness in worker processes (gpfd.user_env): for
// environments stepped in Python, where threads would queue on the GIL. Same results as
// ThreadEvaluator, since each genome's fitness depends on its own seed only.
class PythonBatchEvaluator final : public gp::Evaluator {
 public:
  PythonBatchEvaluator(nb::object evaluate, std::string configText, std::function<void()> done)
      : evaluate_(std::move(evaluate)),
        configText_(std::move(configText)),
        done_(std::move(done)) {}
  ~PythonBatchEvaluator() override {
    nb::gil_scoped_acquire gil;
    evaluate_.reset();
  }

  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override {
    nb::gil_scoped_acquire gil;
    nb::list tasks;
    for (std::size_t i = 0; i < genomes.size(); ++i) {
      const std::string blob = packGenome(*genomes[i]);
      tasks.append(nb::make_tuple(nb::bytes(blob.data(), blob.size()), seeds[i]));
    }
    const nb::object results = evaluate_(configText_, tasks);
    std::vector<double> out;
    for (nb::handle value : results) {
      out.push_back(nb::cast<double>(value));
      if (done_) done_();
    }
    if (out.size() != genomes.size()) {
      throw std::runtime_error(fmt::format(
          "the evaluator returned {} fitness values for {} genomes", out.size(), genomes.size()));
    }
    return out;
  }

 private:
  nb::object evaluate_;
  std::string configText_;
  std::function<void()> done_;
};

// The default results directory of `gpfd evolve`: results/<name>, or results/<name>-N when taken.
std::string freshResultsDir(const std::string& base) {
  std::string dir = base;
  for (int n = 2; std::filesystem::exists(dir); ++n) dir = base + "-" + std::to_string(n);
  return dir;
}

std::vector<std::string> stateNamesOf(const run::ExperimentConfig& config) {
  return env::Registry::global().make(config.env, config.envParams)->stateNames();
}

nb::dict generationDict(const run::GenerationRecord& r, const run::ExperimentConfig& config,
                        const std::vector<std::string>& variables) {
  nb::dict d;
  d["generation"] = r.generation;
  d["best"] = r.best;
  d["mean"] = r.mean;
  d["median"] = r.median;
  d["mean_size"] = r.meanSize;
  d["mean_features"] = r.meanFeatures;
  d["evaluations"] = r.evaluations;
  d["cache_hits"] = r.cacheHits;
  d["seconds"] = r.seconds;
  expr::FeaturesFile best;
  best.env = config.env;
  best.variables = variables;
  best.genome = expr::simplify(r.bestGenome);  // As best/generation-NNNN.features holds it.
  d["best_features"] = nb::cast(FeatureSet(std::move(best), "best"));
  return d;
}

nb::tuple evolve(const std::string& configName, const std::vector<std::string>& overrides,
                 const std::string& out, const std::string& resume, int threads,
                 std::optional<int> generations, nb::object onGeneration, nb::object evaluate) {
  run::DiscoveryOptions options;
  options.outDir = resume.empty() ? out : resume;
  options.threads = threads;
  options.version = kVersion;
  options.revision = kRevision;
  if (!evaluate.is_none()) {
    options.makeEvaluator = [evaluate](const run::EvaluatorSetup& setup) {
      return std::make_unique<PythonBatchEvaluator>(evaluate, setup.configText, setup.onEvaluated);
    };
  }
  std::unique_ptr<run::Discovery> discovery;
  if (!resume.empty()) {
    std::optional<run::ExperimentConfig> expected;
    if (!configName.empty()) expected = app::loadConfig(configName, {});
    discovery = run::Discovery::resume(options, expected, generations);
  } else {
    const auto config = app::loadConfig(configName, overrides);
    if (options.outDir.empty()) options.outDir = freshResultsDir("results/" + config.name);
    discovery = run::Discovery::start(config, options);
  }
  const auto variables = stateNamesOf(discovery->config());
  std::atomic<bool> stop{false};
  {
    nb::gil_scoped_release release;
    discovery->run(
        [&](const run::GenerationRecord& record) {
          nb::gil_scoped_acquire gil;
          // Ctrl-C stops the run once this generation's checkpoint is written.
          if (PyErr_CheckSignals() != 0) throw nb::python_error();
          if (onGeneration.is_none()) return;
          const nb::object verdict =
              onGeneration(generationDict(record, discovery->config(), variables));
          if (PyObject_IsTrue(verdict.ptr()) == 1) stop.store(true);
        },
        stop);
  }
  return nb::make_tuple(options.outDir, discovery->finished());
}

// One LearningTask per config text, for the worker processes' fitness calls.
const run::LearningTask& cachedTask(const std::string& configText) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<run::LearningTask>> tasks;
  const std::lock_guard lock(mutex);
  auto& task = tasks[configText];
  if (!task) {
    task = std::make_unique<run::LearningTask>(run::parseExperimentConfig(configText, "config"),
                                               run::LearningTask::Budget::Trial);
  }
  return *task;
}

double trialFitness(const std::string& configText, const nb::bytes& genome, std::uint64_t seed) {
  const run::LearningTask& task = cachedTask(configText);
  const expr::Genome g = unpackGenome(std::string_view(genome.c_str(), genome.size()),
                                      static_cast<int>(task.stateDim()));
  nb::gil_scoped_release release;
  Rng rng(seed);
  return run::trialFitness(task, g, rng);
}

void checkFor(const FeatureSet& set, const run::LearningTask& task) {
  const auto& env = task.config().env;
  if (!set.file().env.empty() && set.file().env != env) {
    throw InputError("the features are for " + set.file().env + ", not " + env, set.name());
  }
  if (set.file().variables != task.stateNames()) {
    throw InputError(
        fmt::format("the features read {} but {} has {}", fmt::join(set.file().variables, ", "),
                    env, fmt::join(task.stateNames(), ", ")),
        set.name());
  }
}

double fitness(const std::string& configName, const std::vector<std::string>& overrides,
               const FeatureSet& set, std::uint64_t seed) {
  const auto config = app::loadConfig(configName, overrides);
  run::validate(config);
  const run::LearningTask task(config, run::LearningTask::Budget::Trial);
  checkFor(set, task);
  nb::gil_scoped_release release;
  Rng rng(seed);
  return run::trialFitness(task, set.file().genome, rng);
}

// `gpfd assess`'s config: the config's learner (or pg, lpi for Tetris), params routed to the
// environment or the long budget.
run::ExperimentConfig assessConfig(const std::string& configName, const std::string& envName,
                                   const std::map<std::string, std::string>& params, int runs,
                                   int budget, std::uint64_t seed) {
  run::ExperimentConfig config;
  if (!configName.empty()) {
    config = app::loadConfig(configName, {});
    if (!envName.empty() && envName != config.env) {
      throw InputError("the environment differs from the config's (" + config.env + ")", envName);
    }
  } else {
    if (envName.empty()) throw InputError("give an environment or a config", "gpfd.assess");
    config.env = envName;
    config.learner = env::Registry::global().info(envName).defaultLearner;
  }
  std::vector<std::string> assignments;
  for (const auto& [key, value] : params) assignments.push_back(key + "=" + value);
  const auto routed =
      app::routeParams(assignments, env::Registry::global().info(config.env), "params");
  for (const auto& [key, value] : routed.env) config.envParams[key] = value;
  for (const auto& [key, value] : routed.learner) config.assessParams[key] = value;
  if (budget > 0) {
    const auto& learner = rl::LearnerRegistry::global().info(config.learner);
    config.assessParams[learner.budgetParam] = std::to_string(budget);
  }
  if (runs > 0) config.assessRuns = runs;
  config.seed = seed;
  run::validate(config);
  return config;
}

nb::dict assess(const std::string& configName, const std::string& envName,
                const std::map<std::string, std::string>& params, int runs, int budget,
                std::uint64_t seed, int threads, const std::vector<const FeatureSet*>& featureSets,
                bool raw, bool withOriginal, int fourier, const std::string& out) {
  const auto config = assessConfig(configName, envName, params, runs, budget, seed);
  const run::LearningTask task(config, run::LearningTask::Budget::Assessment);
  const std::size_t dim = task.stateDim();
  std::vector<run::FeatureSet> sets;
  if (raw || !featureSets.empty()) {
    sets.push_back({"original", std::make_shared<const features::RawFeatureMap>(dim)});
  }
  for (const FeatureSet* set : featureSets) {
    checkFor(*set, task);
    std::string name = set->name();
    for (const auto& s : sets) {
      if (s.name == name) name += "-" + std::to_string(sets.size());
    }
    const bool asEvolved = config.withOriginal;
    sets.push_back({name + (asEvolved ? "+original" : ""),
                    run::genomeFeatureMap(set->file().genome, dim, asEvolved)});
    if (withOriginal && !asEvolved) {
      sets.push_back({name + "+original", run::genomeFeatureMap(set->file().genome, dim, true)});
    }
  }
  if (fourier > 0) sets.push_back(run::fourierFeatureSet(task, fourier));
  if (sets.empty()) throw InputError("nothing to assess: give features or raw=True", "gpfd.assess");
  if (!out.empty()) createDirectories(out);

  std::vector<run::SetSummary> summary;
  {
    nb::gil_scoped_release release;
    const auto result = run::runAssessment(task, sets, config.assessRuns, config.seed, threads);
    summary = run::summarizeAssessment(result, 0);
    if (!out.empty()) {
      run::writeAssessment(out, result, summary, config.env + ": " + config.learner,
                           config.learner == "lpi" ? "iteration" : "policy update");
    }
  }
  std::map<std::string, std::vector<double>> columns;
  std::vector<std::string> names;
  for (const auto& row : summary) {
    names.push_back(row.name);
    const auto& c = row.vsBaseline;
    const auto& a = row.areaVsBaseline;
    const std::pair<const char*, double> cells[] = {{"runs", row.final.n},
                                                    {"mean_final", row.final.mean},
                                                    {"std", row.final.stddev},
                                                    {"ci95", row.final.halfWidth},
                                                    {"diverged", row.diverged},
                                                    {"welch_t", c.welchT},
                                                    {"welch_p", c.welchP},
                                                    {"mann_whitney_u", c.mannWhitneyU},
                                                    {"mann_whitney_p", c.mannWhitneyP},
                                                    {"cohen_d", c.cohenD},
                                                    {"a12", c.a12},
                                                    {"mean_area", row.area.mean},
                                                    {"area_ci95", row.area.halfWidth},
                                                    {"area_welch_p", a.welchP},
                                                    {"area_mann_whitney_p", a.mannWhitneyP}};
    for (const auto& [key, value] : cells) columns[key].push_back(value);
  }
  nb::dict table;
  table["set"] = names;
  for (auto& [key, values] : columns) table[key.c_str()] = values;
  return table;
}

}  // namespace

void bindDiscovery(nb::module_& m) {
  m.def("evolve", &evolve, nb::arg("config"), nb::arg("overrides"), nb::arg("out"),
        nb::arg("resume"), nb::arg("threads"), nb::arg("generations").none(),
        nb::arg("on_generation").none(), nb::arg("evaluate").none(),
        "Runs (or resumes) a discovery run like `gpfd evolve`; returns (results dir, finished).");
  m.def("trial_fitness", &trialFitness, nb::arg("config_text"), nb::arg("genome"), nb::arg("seed"),
        "run::trialFitness of a packed genome (the worker processes' task).");
  m.def("fitness", &fitness, nb::arg("config"), nb::arg("overrides"), nb::arg("features"),
        nb::arg("seed"), "GP's fitness of a feature set under a config.");
  m.def(
      "resolved_config",
      [](const std::string& config, const std::vector<std::string>& overrides) {
        return run::formatExperimentConfig(app::loadConfig(config, overrides));
      },
      nb::arg("config"), nb::arg("overrides"), "A config, fully resolved, as TOML.");
  m.def("builtin_configs", &app::builtinConfigNames);
  m.def("assess", &assess, nb::arg("config"), nb::arg("env"), nb::arg("params"), nb::arg("runs"),
        nb::arg("budget"), nb::arg("seed"), nb::arg("threads"), nb::arg("features"), nb::arg("raw"),
        nb::arg("with_original"), nb::arg("fourier"), nb::arg("out"),
        "The test protocol of `gpfd assess`; returns the statistics table by column.");
}

}  // namespace gpfd::python
