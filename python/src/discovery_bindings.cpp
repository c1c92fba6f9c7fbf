// python: the bindings of discovery (`gpfd evolve`), GP's fitness of feature sets, and assessment
// (`gpfd assess`) from Python: thin adapters over the service layer (gpfd/service/), which the
// command line calls too, so both give the same results and guarantees (the directory lock
// first). gpfd.discovery.runs wraps them; the evaluator of an environment stepped in Python is
// python_evaluator.hpp, a run's progress evolve_progress.hpp.
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <map>
#include <optional>

#include "bindings.hpp"
#include "evolve_progress.hpp"
#include "feature_set.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/service/assess.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/service/feature_source.hpp"
#include "lockstep_group.hpp"
#include "python_evaluator.hpp"
#include "trial_runner.hpp"

namespace gpfd::python {
namespace {

// Returns (results dir, finished, interruption): the text of gpfd.evolve's KeyboardInterrupt,
// empty unless Ctrl-C stopped the run (the error it surfaced as is dropped: the caller raises it).
nb::tuple evolve(const std::string& config, const std::vector<std::string>& overrides,
                 std::optional<std::string> out, bool force, const std::string& resume, int threads,
                 std::optional<int> generations, std::optional<int> runs, nb::object onGeneration,
                 nb::object evaluate, const nb::object& verbose, nb::object observer,
                 const std::string& outName, const std::string& resumeCommand,
                 nb::object interrupted, const std::string& envJson, const std::string& replay) {
  service::EvolveRequest request;
  request.replay = replay;
  request.config = config;
  request.overrides = overrides;
  request.out = {std::move(out), force, "out"};
  request.resume = resume;
  request.threads = threads;
  request.generations = generations;
  request.runs = runs;
  request.outName = outName;
  request.envJson = envJson;
  if (!evaluate.is_none()) {
    // The request is copied, and the evaluator made, without the GIL: the Python object is held
    // where copies of the function do not touch its reference count.
    request.makeEvaluator = [held = heldWithGil(evaluate)](const run::EvaluatorSetup& setup) {
      const nb::gil_scoped_acquire gil;
      return pythonBatchEvaluator(*held, setup.configText, setup.onEvaluated);
    };
    // An environment stepped in Python: the GP's evaluations and the validation and confirmation
    // trials all go to the evaluator's worker processes (threads of this process would only queue
    // on the GIL); run.json records how many.
    request.trialRunner = pythonTrialRunner(evaluate);
    request.threads = nb::cast<int>(evaluate.attr("workers"));
  }
  std::atomic<bool> stop{false};
  PythonProgress progress(std::move(onGeneration), verbose, std::move(observer), resumeCommand,
                          interrupted, stop);
  service::EvolveResult result;
  std::optional<Interruption> interruption;
  {
    nb::gil_scoped_release release;
    // The polling thread ends before the GIL is taken back, whatever happens.
    const struct StopPolling {
      PythonProgress& p;
      ~StopPolling() { p.stopPolling(); }
    } stopPolling{progress};
    try {
      result = service::evolve(request, progress, stop);
    } catch (...) {
      interruption = progress.interruption();
      // Ctrl-C before any run started (the config read, the states sampled): nothing was kept.
      if (!interruption && progress.isInterruption()) interruption = Interruption{};
      if (!interruption) throw;
    }
  }
  if (interruption) {
    const std::string text = interruption->dir.empty()
                                 ? std::string(
                                       "gpfd.evolve interrupted before its first "
                                       "generation: nothing is kept")
                                 : interruptionText(*interruption, resumeCommand);
    return nb::make_tuple(interruption->resumeDir, false, text);
  }
  return nb::make_tuple(result.dir, result.finished, std::string());
}

service::FeatureSource sourceOf(const FeatureSet& set) {
  return {.name = set.name(), .path = {}, .file = set.file()};
}

std::vector<double> fitnessOfEach(const std::string& config,
                                  const std::vector<std::string>& overrides,
                                  const std::vector<const FeatureSet*>& sets, std::uint64_t seed) {
  std::vector<service::FeatureSource> sources;
  for (const FeatureSet* set : sets) sources.push_back(sourceOf(*set));
  nb::gil_scoped_release release;
  return service::trialFitnesses(config, overrides, sources, seed, playInGroup);
}

nb::dict assess(const std::string& config, const std::vector<std::string>& overrides,
                const std::string& env, const std::map<std::string, std::string>& params, int runs,
                int budget, std::uint64_t seed, int threads,
                const std::vector<const FeatureSet*>& featureSets, bool raw, bool withOriginal,
                int fourier, std::optional<std::string> out, bool force, nb::object evaluator) {
  service::AssessRequest request;
  request.env = env;
  request.config = config;
  request.overrides = overrides;
  for (const FeatureSet* set : featureSets) request.features.push_back(sourceOf(*set));
  request.raw = raw;
  request.withOriginal = withOriginal;
  request.fourier = fourier;
  request.runs = runs;
  request.budget = budget;
  for (const auto& [key, value] : params) request.params.push_back(key + "=" + value);
  request.seed = seed;
  request.threads = threads;
  // An environment stepped in Python: the runs go to the evaluator's worker processes.
  if (!evaluator.is_none()) request.trialRunner = pythonTrialRunner(std::move(evaluator));
  request.write = out.has_value();
  request.out = {std::move(out), force, "out"};
  request.where = "gpfd.assess";
  service::AssessResult result;
  {
    nb::gil_scoped_release release;
    result = service::assess(request);
  }
  std::map<std::string, std::vector<double>> columns;
  std::vector<std::string> names;
  for (const auto& row : result.summary) {
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
  m.def("evolve", &evolve, nb::arg("config"), nb::arg("overrides"), nb::arg("out").none(),
        nb::arg("force"), nb::arg("resume"), nb::arg("threads"), nb::arg("generations").none(),
        nb::arg("runs").none(), nb::arg("on_generation").none(), nb::arg("evaluate").none(),
        nb::arg("verbose").none(), nb::arg("observer").none() = nb::none(),
        nb::arg("out_name") = "", nb::arg("resume_command") = "gpfd.evolve(resume=\"{}\")",
        nb::arg("interrupted").none() = nb::none(), nb::arg("env_json") = "",
        nb::arg("replay") = "",
        "Runs (or resumes, or replays) discovery through the service layer, like `gpfd evolve`; "
        "returns "
        "(results dir, finished, interruption: the text of the KeyboardInterrupt to raise when "
        "Ctrl-C stopped "
        "it, else empty). env_json: run.json's \"env\" of each run started (a JSON object); "
        "replay: the finished run to rerun with its sizes.");
  m.def("trial_fitness_group", &trialFitnessGroupOf, nb::arg("config_text"), nb::arg("tasks"),
        "run::trialFitness of each (genome wire record, seed), played in one lockstep group: the "
        "evaluations' episodes share one vector environment (the worker processes' task).");
  m.def("fitness_of_each", &fitnessOfEach, nb::arg("config"), nb::arg("overrides"),
        nb::arg("features"), nb::arg("seed"),
        "GP's fitness of each feature set under a config, the same seed, in one lockstep group.");
  m.def(
      "resolved_config",
      [](const std::string& config, const std::vector<std::string>& overrides) {
        return run::formatExperimentConfig(service::loadConfig(config, overrides));
      },
      nb::arg("config"), nb::arg("overrides"), "A config, fully resolved, as TOML.");
  m.def("builtin_configs", &service::builtinConfigNames);
  m.def(
      "signed_rank_test",
      [](const std::vector<double>& values) {
        const auto test = run::wilcoxonSignedRank(values);
        return nb::make_tuple(test.n, test.wPlus, test.p, test.median);
      },
      nb::arg("values"),
      "run::wilcoxonSignedRank: (non-zero values, W+, two-sided p, median), the test of "
      "gpfd's method-level verdict.");
  m.def("assess", &assess, nb::arg("config"), nb::arg("overrides"), nb::arg("env"),
        nb::arg("params"), nb::arg("runs"), nb::arg("budget"), nb::arg("seed"), nb::arg("threads"),
        nb::arg("features"), nb::arg("raw"), nb::arg("with_original"), nb::arg("fourier"),
        nb::arg("out").none(), nb::arg("force"), nb::arg("evaluator").none() = nb::none(),
        "The test protocol of `gpfd assess`; returns the statistics table by column.");
}

}  // namespace gpfd::python
