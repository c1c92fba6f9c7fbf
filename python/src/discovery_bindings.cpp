// python: discovery (`gpfd evolve`), GP's fitness of one feature set, and assessment
// (`gpfd assess`) from Python: thin adapters over the service layer (gpfd/service/), which the
// command line calls too, so both give the same results and guarantees (the directory lock
// first). gpfd.discovery wraps them.
#include <fmt/format.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <stop_token>
#include <thread>

#include "bindings.hpp"
#include "feature_set.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/expr/wire.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/service/assess.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/service/evolve_text.hpp"
#include "gpfd/service/feature_source.hpp"
#include "lockstep_group.hpp"
#include "trial_runner.hpp"

namespace gpfd::python {
namespace {

// Fitness evaluation by a Python callable, evaluate(config_text, [(genome record, seed), ...]) ->
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
      const std::string blob = expr::wire::encodeGenome(*genomes[i]);
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

std::vector<std::string> stateNamesOf(const run::ExperimentConfig& config) {
  return env::Registry::global().make(config.env, config.envParams)->stateNames();
}

nb::dict generationDict(const run::GenerationRecord& r, const run::Discovery& discovery,
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
  d["generations"] = discovery.stage().generations;  // As a time budget's deadline refits them.
  expr::FeaturesFile best;
  best.env = discovery.config().env;
  best.variables = variables;
  best.genome = discovery.asLearnerSees(r.bestGenome);  // As best/generation-NNNN.features.
  d["best_features"] = nb::cast(FeatureSet(std::move(best), "best"));
  return d;
}

// Text to one of Python's streams ("stdout", "stderr"), so that it shows in notebooks too.
service::TextSink pythonStream(const char* name) {
  return [name](const std::string& text) {
    nb::gil_scoped_acquire gil;
    const nb::object stream = nb::module_::import_("sys").attr(name);
    stream.attr("write")(text);
    stream.attr("flush")();
  };
}

// Where a run stopped by Ctrl-C was (PythonProgress::runStopped), for the text of gpfd.evolve's
// KeyboardInterrupt.
struct Interruption {
  std::string dir, resumeDir, label;
  std::optional<int> lastGeneration;  // The last complete generation (checkpointed), if any.
  run::RunStage::Kind stage = run::RunStage::Generations;
};

// gpfd.evolve's view of a run: the per-generation callback (a true return value stops the run),
// Ctrl-C checked after each generation, the command's text when verbose, only the verdict when
// `verbose` is None without a display (what stops a run is always said, on stderr), and a
// progress display (`observer`, gpfd.progress.EvolveBar) when one is given: it is told when a run
// starts and ends and, every half second from a thread of its own, the running stage; the
// command's header and outcome lines are printed around it. A run that an interruption stops
// (KeyboardInterrupt, or any error while `interrupted()` is true: Ctrl-C came) says nothing: its
// Interruption is kept for gpfd.evolve's KeyboardInterrupt.
class PythonProgress final : public service::EvolveProgress {
 public:
  PythonProgress(nb::object onGeneration, std::optional<bool> verbose, nb::object observer,
                 const std::string& resumeCommand, nb::object interrupted, std::atomic<bool>& stop)
      : onGeneration_(std::move(onGeneration)),
        observer_(std::move(observer)),
        interrupted_(std::move(interrupted)),
        text_({.out = pythonStream("stdout"),
               .err = pythonStream("stderr"),
               .terminal = false,
               .quiet = verbose == false,
               .outcomeOnly = !verbose.has_value() && observer_.is_none(),
               .resumeCommand = resumeCommand}),
        stop_(stop) {}
  ~PythonProgress() override { stopPolling(); }

  void runStarted(const run::Discovery& d, const std::string& dir,
                  const std::string& label) override {
    label_ = label;
    variables_ = stateNamesOf(d.config());
    text_.runStarted(d, dir, label);
    if (observer_.is_none()) return;
    {
      nb::gil_scoped_acquire gil;
      nb::dict info;
      info["label"] = label;
      info["dir"] = dir;
      info["generations"] = d.config().gp.generations;
      info["done"] = d.history().size();  // Generations done before (a resumed run).
      info["population"] = d.populationSize();
      observer_.attr("run_started")(info);
    }
    discovery_ = &d;
    poller_ = std::jthread([this](const std::stop_token& token) { poll(token); });
  }
  void generationDone(const run::Discovery& d, const run::GenerationRecord& record,
                      const std::string& label) override {
    if (observer_.is_none()) text_.generationDone(d, record, label);
    nb::gil_scoped_acquire gil;
    // Ctrl-C stops the run once this generation's checkpoint is written.
    if (PyErr_CheckSignals() != 0) throw nb::python_error();
    if (onGeneration_.is_none()) return;
    const nb::object verdict = onGeneration_(generationDict(record, d, variables_));
    if (PyObject_IsTrue(verdict.ptr()) == 1) stop_.store(true);
  }
  void runStopped(const run::Discovery& d, const std::string& dir, const std::string& resumeDir,
                  bool error) override {
    runEnded(false);
    if (error && isInterruption()) {
      const auto& history = d.history();
      interruption_ = Interruption{dir, resumeDir, label_, std::nullopt, d.stage().kind};
      if (!history.empty()) interruption_->lastGeneration = history.back().generation;
      return;
    }
    text_.runStopped(d, dir, resumeDir, error);
  }
  void runFinished(const run::RunOutcome& o, const std::string& dir,
                   const std::string& label) override {
    runEnded(true);
    text_.runFinished(o, dir, label);
  }
  void setFinished(const std::vector<run::RunOutcome>& o, const std::string& dir) override {
    text_.setFinished(o, dir);
  }
  void alreadyComplete(const std::string& dir, int generations) override {
    text_.alreadyComplete(dir, generations);
  }
  void preparedRun(const std::string& text) override { text_.preparedRun(text); }
  // A stage before the run (the learner's choice, a budget's measurement): said, and shown by the
  // display where it has `phase`.
  void preparing(const std::string& phase) override {
    text_.preparing(phase);
    if (observer_.is_none()) return;
    nb::gil_scoped_acquire gil;
    try {
      if (nb::hasattr(observer_, "phase")) observer_.attr("phase")(phase);
    } catch (nb::python_error& e) {
      e.discard_as_unraisable("gpfd.evolve's progress display");
    }
  }

  // Whether the error being handled is an interruption: KeyboardInterrupt, or any error after
  // Ctrl-C (which may surface as another). Call within a catch block, without the GIL.
  bool isInterruption() {
    nb::gil_scoped_acquire gil;
    try {
      throw;
    } catch (nb::python_error& e) {
      if (e.matches(PyExc_KeyboardInterrupt)) return true;
    } catch (...) {
    }
    return !interrupted_.is_none() && nb::cast<bool>(interrupted_());
  }

  // The run stopped by an interruption, if one was.
  const std::optional<Interruption>& interruption() const { return interruption_; }

  // Ends the polling thread; call without the GIL, which the thread takes.
  void stopPolling() {
    if (!poller_.joinable()) return;
    poller_.request_stop();
    poller_.join();
  }

 private:
  // The running stage to the observer every half second, until stopped. An error in the
  // observer ends the polling (reported as unraisable), never the run.
  void poll(const std::stop_token& token) {
    std::mutex mutex;
    std::condition_variable_any wake;
    std::unique_lock lock(mutex);
    while (true) {
      wake.wait_for(lock, token, std::chrono::milliseconds(500), [] { return false; });
      if (token.stop_requested()) return;
      nb::gil_scoped_acquire gil;
      try {
        tellStage();
      } catch (nb::python_error& e) {
        e.discard_as_unraisable("gpfd.evolve's progress display");
        return;
      }
    }
  }

  // Needs the GIL.
  void tellStage() {
    const run::RunStage stage = discovery_->stage();
    observer_.attr("poll")(run::stageName(stage.kind), stage.done, stage.total, stage.generations);
  }

  // The stage where the run ended (so that the display shows it whatever the timing), then the
  // end. A display error is reported as unraisable: the run's own outcome or error goes on.
  void runEnded(bool finished) {
    if (observer_.is_none() || discovery_ == nullptr) return;
    stopPolling();
    nb::gil_scoped_acquire gil;
    try {
      tellStage();
      observer_.attr("run_ended")(finished);
    } catch (nb::python_error& e) {
      e.discard_as_unraisable("gpfd.evolve's progress display");
    }
    discovery_ = nullptr;
  }

  nb::object onGeneration_;
  nb::object observer_;
  nb::object interrupted_;
  service::EvolveText text_;
  std::string label_;  // Of the running run.
  std::optional<Interruption> interruption_;
  std::atomic<bool>& stop_;
  std::vector<std::string> variables_;
  const run::Discovery* discovery_ = nullptr;  // The running one (runStarted to its end).
  std::jthread poller_;
};

// The text of gpfd.evolve's KeyboardInterrupt: where the run was, and how to continue it (or that
// nothing was kept).
std::string interruptionText(const Interruption& i, const std::string& resumeCommand) {
  namespace fs = std::filesystem;
  std::string where;
  if (i.stage == run::RunStage::Generations) {
    where = fmt::format("generation {}", i.lastGeneration ? *i.lastGeneration + 1 : 0);
  } else {
    where = fmt::format("{} (after generation {})", run::stageName(i.stage),
                        i.lastGeneration.value_or(-1));
  }
  std::error_code ec;
  if (!fs::exists(i.dir + "/config.toml", ec)) {
    return fmt::format(
        "gpfd.evolve interrupted in {}{}, before its first checkpoint: nothing is "
        "kept; run it again to start over",
        i.label, where);
  }
  const std::string back =
      i.lastGeneration
          ? fmt::format("continues from the checkpoint of generation {}", *i.lastGeneration)
          : std::string("starts over (no generation was complete)");
  return fmt::format("gpfd.evolve interrupted in {}{}; the run {} with: {}", i.label, where, back,
                     fmt::format(fmt::runtime(resumeCommand), i.resumeDir));
}

// Returns (results dir, finished, interruption): the text of gpfd.evolve's KeyboardInterrupt,
// empty unless Ctrl-C stopped the run (the error it surfaced as is dropped: the caller raises it).
nb::tuple evolve(const std::string& config, const std::vector<std::string>& overrides,
                 std::optional<std::string> out, bool force, const std::string& resume, int threads,
                 std::optional<int> generations, std::optional<int> runs, nb::object onGeneration,
                 nb::object evaluate, std::optional<bool> verbose, nb::object observer,
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
      return std::make_unique<PythonBatchEvaluator>(*held, setup.configText, setup.onEvaluated);
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

// run::trialFitness of each genome (a gpfd/expr/wire.hpp record) with Rng(seed), all in one
// lockstep group (lockstep_group.hpp): the worker processes' task (a group of one where there is no
// vector form).
std::vector<double> trialFitnessGroupOf(
    const std::string& configText, const std::vector<std::pair<nb::bytes, std::uint64_t>>& tasks) {
  // Kept while in use: an environment's step may register a name, which forgets cached tasks.
  const auto owned = cachedTask(configText, run::LearningTask::Budget::Trial);
  const run::LearningTask& task = *owned;
  std::vector<expr::Genome> genomes;
  std::vector<std::uint64_t> seeds;
  for (const auto& [genome, seed] : tasks) {
    genomes.push_back(expr::wire::decodeGenome(std::string_view(genome.c_str(), genome.size()),
                                               static_cast<int>(task.stateDim())));
    seeds.push_back(seed);
  }
  nb::gil_scoped_release release;
  std::vector<double> fitness(genomes.size(), 0.0);
  playInGroup(genomes.size(), [&](std::size_t i) {
    Rng rng(seeds[i]);
    fitness[i] = run::trialFitness(task, genomes[i], rng);
  });
  return fitness;
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
