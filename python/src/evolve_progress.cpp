// python: gpfd.evolve's progress (evolve_progress.hpp).
#include "evolve_progress.hpp"

#include <fmt/format.h>
#include <nanobind/stl/string.h>

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <mutex>

#include "feature_set.hpp"
#include "gpfd/env/environment.hpp"

namespace gpfd::python {
namespace {

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

}  // namespace

PythonProgress::PythonProgress(nb::object onGeneration, const nb::object& verbose,
                               nb::object observer, const std::string& resumeCommand,
                               nb::object interrupted, std::atomic<bool>& stop)
    : onGeneration_(std::move(onGeneration)),
      observer_(std::move(observer)),
      interrupted_(std::move(interrupted)),
      text_({.out = pythonStream("stdout"),
             .err = pythonStream("stderr"),
             .terminal = false,
             .quiet = !verbose.is_none() && !nb::cast<bool>(verbose),
             .outcomeOnly = verbose.is_none() && observer_.is_none(),
             .resumeCommand = resumeCommand}),
      stop_(stop) {}

void PythonProgress::runStarted(const run::Discovery& d, const std::string& dir,
                                const std::string& label) {
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

void PythonProgress::generationDone(const run::Discovery& d, const run::GenerationRecord& record,
                                    const std::string& label) {
  if (observer_.is_none()) text_.generationDone(d, record, label);
  nb::gil_scoped_acquire gil;
  // Ctrl-C stops the run once this generation's checkpoint is written.
  if (PyErr_CheckSignals() != 0) throw nb::python_error();
  if (onGeneration_.is_none()) return;
  const nb::object verdict = onGeneration_(generationDict(record, d, variables_));
  if (PyObject_IsTrue(verdict.ptr()) == 1) stop_.store(true);
}

void PythonProgress::runStopped(const run::Discovery& d, const std::string& dir,
                                const std::string& resumeDir, bool error) {
  runEnded(false);
  if (error && isInterruption()) {
    const auto& history = d.history();
    interruption_ = Interruption{dir, resumeDir, label_, std::nullopt, d.stage().kind};
    if (!history.empty()) interruption_->lastGeneration = history.back().generation;
    return;
  }
  text_.runStopped(d, dir, resumeDir, error);
}

void PythonProgress::runFinished(const run::RunOutcome& o, const std::string& dir,
                                 const std::string& label) {
  runEnded(true);
  text_.runFinished(o, dir, label);
}

void PythonProgress::preparing(const std::string& phase) {
  text_.preparing(phase);
  if (observer_.is_none()) return;
  nb::gil_scoped_acquire gil;
  try {
    if (nb::hasattr(observer_, "phase")) observer_.attr("phase")(phase);
  } catch (nb::python_error& e) {
    e.discard_as_unraisable("gpfd.evolve's progress display");
  }
}

bool PythonProgress::isInterruption() {
  nb::gil_scoped_acquire gil;
  try {
    throw;
  } catch (nb::python_error& e) {
    if (e.matches(PyExc_KeyboardInterrupt)) return true;
  } catch (...) {
  }
  return !interrupted_.is_none() && nb::cast<bool>(interrupted_());
}

void PythonProgress::stopPolling() {
  if (!poller_.joinable()) return;
  poller_.request_stop();
  poller_.join();
}

void PythonProgress::poll(const std::stop_token& token) {
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

void PythonProgress::tellStage() {
  const run::RunStage stage = discovery_->stage();
  observer_.attr("poll")(run::stageName(stage.kind), stage.done, stage.total, stage.generations);
}

void PythonProgress::runEnded(bool finished) {
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

}  // namespace gpfd::python
