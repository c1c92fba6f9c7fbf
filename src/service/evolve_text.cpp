#include "gpfd/service/evolve_text.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "gpfd/run/validation.hpp"

namespace gpfd::service {
namespace {

std::string meanSe(const run::Summary& s) {
  return fmt::format("{:.6g} +- {:.3g}", s.mean, s.standardError());
}

}  // namespace

std::string formatDuration(double seconds) {
  // Rounded to the unit shown first, so that 299.6 s reads 5m00s, not 4m60s.
  if (seconds < 89.5) return fmt::format("{:.0f}s", seconds);
  const double wholeSeconds = std::round(seconds);
  if (wholeSeconds < 5400) {
    return fmt::format("{:.0f}m{:02.0f}s", std::floor(wholeSeconds / 60),
                       std::fmod(wholeSeconds, 60));
  }
  const double wholeMinutes = std::round(seconds / 60);
  return fmt::format("{:.0f}h{:02.0f}m", std::floor(wholeMinutes / 60),
                     std::fmod(wholeMinutes, 60));
}

EvolveText::EvolveText(Options options) : o_(std::move(options)) {}
EvolveText::~EvolveText() { stopStatus(); }

void EvolveText::runStarted(const run::Discovery& discovery, const std::string& dir,
                            const std::string& label) {
  total_ = 0.0;
  if (o_.quiet || o_.outcomeOnly) return;
  const auto& config = discovery.config();
  o_.out(fmt::format(
      "{}gpfd evolve: {} ({} on {}), population {}, generations {}, seed {}, results in {}\n",
      label, config.name, config.learner, config.env, config.gp.population, config.gp.generations,
      config.seed, dir));
  if (!o_.terminal) return;
  // On a terminal, a status line shows the evaluations of the running generation, then the
  // trainings of validation and confirmation, with the time the stage has taken so far.
  running_.store(true);
  status_ = std::jthread([this, &discovery, label] {
    auto start = std::chrono::steady_clock::now();
    auto kind = run::RunStage::Generations;
    while (running_.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      const auto stage = discovery.stage();
      if (stage.kind != kind) {
        kind = stage.kind;
        start = std::chrono::steady_clock::now();
      }
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (kind == run::RunStage::Generations) {
        o_.out(fmt::format("\r\033[K  {}generation {} of {}: {}/{} evaluated, {}", label,
                           discovery.history().size(), stage.generations, stage.done, stage.total,
                           formatDuration(elapsed)));
      } else {
        o_.out(fmt::format("\r\033[K  {}{}: {}/{} trainings done, {}", label, run::stageName(kind),
                           stage.done, stage.total, formatDuration(elapsed)));
      }
    }
  });
}

void EvolveText::stopStatus() {
  if (!status_.joinable()) return;
  running_.store(false);
  status_.join();
  o_.out("\r\033[K");
}

void EvolveText::generationDone(const run::Discovery& discovery, const run::GenerationRecord& r,
                                const std::string& label) {
  total_ += r.seconds;
  if (o_.quiet || o_.outcomeOnly) return;
  const int remaining = discovery.config().gp.generations - 1 - r.generation;
  const double perGeneration = total_ / static_cast<double>(r.generation + 1);
  o_.out(fmt::format(
      "{}{}gen {:3d}  best {:.6g}  mean {:.6g}  features {:.2f}  size {:.1f}  "
      "evals {} (+{} cached, {} re-evaluated{})  {}  ETA {}\n",
      o_.terminal ? "\r\033[K" : "", label, r.generation, r.best, r.mean, r.meanFeatures,
      r.meanSize, r.evaluations - r.reevaluations, r.cacheHits, r.reevaluations,
      r.promotions > 0 ? fmt::format(", {} at longer rungs", r.promotions) : std::string(),
      formatDuration(r.seconds), formatDuration(perGeneration * remaining)));
}

void EvolveText::runStopped(const run::Discovery& discovery, const std::string& dir,
                            const std::string& resumeDir, bool error) {
  stopStatus();
  const auto& history = discovery.history();
  const std::string resume = fmt::format(fmt::runtime(o_.resumeCommand), resumeDir);
  if (error) {
    if (history.empty()) return;
    o_.err(
        fmt::format("gpfd evolve stopped after generation {}; its checkpoint is written. Continue "
                    "with: {}\n",
                    history.back().generation, resume));
    return;
  }
  o_.err(
      fmt::format("interrupted after generation {}; the checkpoint is written. Continue with: {}\n",
                  history.empty() ? -1 : history.back().generation, resume));
  if (!history.empty()) {
    o_.err(fmt::format(
        "note: {}/best.features holds the GP's best genome so far (GP fitness {:.6g}, a biased "
        "best-of-run estimate): it is NOT validated against the original variables; resuming "
        "to the end validates and confirms\n",
        dir, history.back().best));
  }
}

void EvolveText::runFinished(const run::RunOutcome& o, const std::string& dir,
                             const std::string& label) {
  stopStatus();
  if (o_.quiet) return;
  if (!o.validated) {
    o_.out(fmt::format(
        "{}best fitness {} (GP's own estimate, not validated); features in {}/best.features\n",
        label, o.gpBest, dir));
  } else if (o.originalWon && o.noLearning.winnerNoBetter) {
    o_.out(fmt::format(
        "{}the validation winner is not significantly better than no learning on the {} seeds "
        "(difference {:.4g}, p = {:.3g}): not a discovery; {}/best.features holds the original "
        "variables\n",
        label, o.confirmed ? "confirmation" : "validation", o.noLearning.winner.meanDifference,
        o.noLearning.winner.p, dir));
  } else if (o.originalWon) {
    o_.out(
        fmt::format("{}no discovered feature set beat the original variables on {} (original {}); "
                    "{}/best.features holds the original variables\n",
                    label, o.confirmed ? "validation and confirmation" : "validation",
                    meanSe(o.original), dir));
  } else {
    // The score's name as best.features gives it: confirmed (unbiased) or selection (biased);
    // a confirmation that found the winner no better than the original variables did not
    // confirm it.
    const bool better = o.vsOriginal.p < 0.05 && o.vsOriginal.meanDifference > 0.0;
    o_.out(fmt::format(
        "{}{}: {} vs original {} on {} paired fresh trials: {}; features in {}/best.features\n",
        label,
        !o.confirmed ? "selection"
        : better     ? "confirmed"
                     : "not confirmed",
        meanSe(o.winner), meanSe(o.original), o.winner.n,
        run::comparisonVerdict(o.vsOriginal, "the original variables",
                               o.confirmed ? "the confirmation seeds" : "the validation seeds"),
        dir));
  }
  if (o.validated && o.noLearning.learnerHarms) {
    o_.out(fmt::format(
        "{}warning: the learner harms: the original variables ({}) do worse than no learning, a "
        "policy that ignores the state ({}; p = {:.3g}); its step sizes or budget need "
        "changing\n",
        label, meanSe(o.original), meanSe(o.noLearning.noLearning), o.noLearning.original.p));
  }
}

void EvolveText::setFinished(const std::vector<run::RunOutcome>& outcomes, const std::string& dir) {
  if (o_.quiet) return;
  int discovered = 0, significant = 0, harms = 0, noBetter = 0;
  bool confirmed = false;
  std::vector<double> differences;
  for (const auto& o : outcomes) {
    if (!o.validated) continue;
    confirmed = confirmed || o.confirmed;
    harms += o.noLearning.learnerHarms ? 1 : 0;
    noBetter += o.noLearning.winnerNoBetter ? 1 : 0;
    differences.push_back(o.vsOriginal.meanDifference);
    if (o.originalWon) continue;
    ++discovered;
    if (o.vsOriginal.p < 0.05) ++significant;
  }
  if (differences.empty()) {
    o_.out(fmt::format("{} runs done (not validated); per-run results in {}/runs.csv\n",
                       outcomes.size(), dir));
    return;
  }
  const auto test = run::wilcoxonSignedRank(differences);
  o_.out(fmt::format(
      "{} runs: a discovered set beat the original variables on {} in {} ({} with "
      "p < 0.05); median difference {:.4g} (Wilcoxon signed-rank over runs p = {:.3g}); per-run "
      "results in {}/runs.csv\n",
      outcomes.size(), confirmed ? "confirmation" : "validation", discovered, significant,
      test.median, test.p, dir));
  if (noBetter > 0) {
    o_.out(fmt::format(
        "{} of {} runs' winners were not significantly better than no learning: not returned as "
        "discoveries\n",
        noBetter, outcomes.size()));
  }
  if (harms > 0) {
    o_.out(fmt::format(
        "warning: the learner harms in {} of {} runs: on the original variables it does worse "
        "than no learning, a policy that ignores the state (p < 0.05); its step sizes or budget "
        "need changing\n",
        harms, outcomes.size()));
  }
}

void EvolveText::preparedRun(const std::string& text) {
  if (!o_.quiet) o_.out(text);
}

void EvolveText::preparing(const std::string& phase) {
  if (!o_.quiet && !o_.outcomeOnly) o_.out("gpfd evolve: " + phase + "\n");
}

void EvolveText::alreadyComplete(const std::string& dir, int generations) {
  o_.err(
      fmt::format("the run in {0} is already complete (generations: {1}); pass --generations N "
                  "(more than {1}) to extend it\n",
                  dir, generations));
}

}  // namespace gpfd::service
