#include "gpfd/service/evolve.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <limits>
#include <string_view>

#include "gpfd/expr/genome.hpp"
#include "gpfd/run/learner_choice.hpp"
#include "gpfd/run/replay.hpp"
#include "gpfd/run/stored_config.hpp"
#include "gpfd/run/time_budget.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/resources.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/version.hpp"

namespace gpfd::service {
namespace {
namespace fs = std::filesystem;

// Runs (or continues) one run; whether it finished. `number` is its place in a set (1 alone).
bool runOne(run::Discovery& discovery, const std::string& dir, const std::string& label, int number,
            const std::string& resumeDir, EvolveProgress& progress, const std::atomic<bool>& stop) {
  progress.runStarted(discovery, dir, label);
  try {
    discovery.run(
        [&](const run::GenerationRecord& r) { progress.generationDone(discovery, r, label); },
        stop);
  } catch (...) {
    // An error during the run (a worker's, a full disk) leaves the last generation's checkpoint.
    progress.runStopped(discovery, dir, resumeDir, true);
    throw;
  }
  if (!discovery.finished()) {
    progress.runStopped(discovery, dir, resumeDir, false);
    return false;
  }
  progress.runFinished(run::outcomeOf(discovery, number), dir, label);
  return true;
}

// Runs (or continues) runs 1..runs of `base` in options.outDir, then sums them up.
// With a time budget (options.deadline: run 1's), run r's deadline is r - 1 shares of
// `perRunSeconds` later.
EvolveResult runSet(const run::ExperimentConfig& base, int runs,
                    const run::DiscoveryOptions& options, std::optional<int> generations,
                    EvolveProgress& progress, const std::atomic<bool>& stop,
                    double perRunSeconds = 0.0) {
  EvolveResult result{options.outDir, false, {}};
  for (int r = 1; r <= runs; ++r) {
    run::ExperimentConfig config = base;
    config.seed = run::runSeed(base.seed, r);
    run::DiscoveryOptions one = options;
    one.outDir = options.outDir + "/" + run::runDirName(r, runs);
    if (options.deadline) {
      *one.deadline += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>((r - 1) * perRunSeconds));
    }
    const DirectoryLock lock = lockDirectory(one.outDir);  // Also against a resume of it.
    const auto discovery = openRun(config, one, generations);
    const std::string label = fmt::format("[run {}/{}] ", r, runs);
    if (!runOne(*discovery, one.outDir, label, r, options.outDir, progress, stop)) return result;
    result.outcomes.push_back(run::outcomeOf(*discovery, r));
    writeFileAtomically(options.outDir + "/runs.csv", run::formatRunsCsv(result.outcomes));
  }
  progress.setFinished(result.outcomes, options.outDir);
  result.finished = true;
  return result;
}

// Whether `overrides` (key=value, the key as the config reads it: no spaces) set `key`.
bool givesKey(const std::vector<std::string>& overrides, std::string_view key) {
  return std::any_of(overrides.begin(), overrides.end(), [&](const std::string& o) {
    return std::string_view(o).substr(0, o.find('=')) == key;
  });
}

bool givesSizes(const EvolveRequest& request) {
  return request.generations || givesKey(request.overrides, "gp.population") ||
         givesKey(request.overrides, "gp.generations");
}

// The config a resume is checked against: a config with a time budget stands for the sizes
// that the budget chose when the run started, one with learner.choose for the settings chosen
// (both stored in DIR/config.toml).
std::optional<run::ExperimentConfig> expectedConfig(const EvolveRequest& request,
                                                    const std::string& dir) {
  if (request.config.empty()) return std::nullopt;
  auto expected = loadConfig(request.config, {});
  const std::string stored = dir + "/config.toml";
  if (!fs::exists(stored)) return expected;
  const auto chosen = run::loadStoredExperimentConfig(stored);
  auto candidates = run::learnerCandidates(expected);
  candidates.insert(candidates.end(), expected.learnerFallbacks.begin(),
                    expected.learnerFallbacks.end());
  // Another learner chosen: the first candidate naming it, its budgets matched as the choice
  // matched them.
  const auto other = std::find_if(candidates.begin(), candidates.end(), [&](const auto& c) {
    const auto learner = run::candidateLearner(expected, c);
    return learner != expected.learner && learner == chosen.learner;
  });
  if (other != candidates.end()) {
    expected = run::withCandidate(expected, *other);
  } else {
    for (const auto& candidate : candidates) {
      for (const auto& [key, ignored] : candidate) {
        const auto value = chosen.learnerParams.find(key);
        if (value != chosen.learnerParams.end()) expected.learnerParams[key] = value->second;
      }
    }
  }
  expected.learnerChoices.clear();
  expected.learnerAlternatives.clear();
  expected.learnerFallbacks.clear();
  if (expected.timeBudget > 0.0) {
    run::BudgetSizes sizes;
    sizes.population = chosen.gp.population;
    sizes.generations = chosen.gp.generations;
    sizes.candidates = chosen.validation.candidates;
    sizes.seeds = chosen.validation.seeds;
    sizes.confirmSeeds = chosen.validation.confirmSeeds;
    expected = run::withSizes(expected, sizes);
  }
  return expected;
}

constexpr const char* kBudgetWhere = "time_budget (--time-budget)";

// The whole training's budget (LearningTask::Budget) the learner's choice trains under.
run::LearningTask::Budget choiceBudget(const run::ExperimentConfig& config) {
  return config.validation.confirms() ? run::LearningTask::Budget::Confirmation
                                      : run::LearningTask::Budget::Validation;
}

// Chooses the learner's settings of learner.choose on the task (run/learner_choice.hpp), with
// the trial runner the run will use, within run::kChoiceShare of a time budget; says what it
// chose and records it for run.json, and what it took in `spent`. InputError where nothing
// learns (run::LearnerChoice::nothingLearns), and under a budget where the first training,
// predicted from one of a single update, tells that `runs` cannot fit, before it is played.
run::ExperimentConfig chooseLearner(const run::ExperimentConfig& config, int runs,
                                    run::DiscoveryOptions& options, run::BudgetSpent& spent,
                                    EvolveProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  // Refused where, were the choice to take nothing more, the measurement and the smallest run
  // would not fit in twice what is left: before the choice plays a first training that fits its
  // share but not the call (Swimmer-v5 in Python: one of 4 calls played one, refused after 95.5 s
  // of 180; it needed 55 times the budget). Twice, as the prediction scales the one-update
  // training's fixed cost with the rest (a Python toy task: 0.24 s, mostly the first call's), and
  // the choice's own measurement refuses the calls nearer the line.
  constexpr double kPredictionTolerance = 2.0;
  const auto refuseFromPrediction = [&](double firstTraining) {
    run::BudgetSpent predicted = spent;
    predicted.choice =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    predicted.choiceFirst = firstTraining;
    predicted.choiceFirstPredicted = true;
    const auto first = run::withCandidate(config, run::learnerCandidates(config).at(0));
    const double one = run::trialSecondsFrom(first, firstTraining, choiceBudget(first));
    run::refuseBeforeMeasuring(first, one, options.threads,
                               kPredictionTolerance * (config.timeBudget - predicted.choice),
                               predicted, kBudgetWhere, runs, true);
  };
  run::ThreadTrialRunner threads(options.threads);
  run::TrialRunner& runner = options.trialRunner ? *options.trialRunner : threads;
  const double allowance = config.timeBudget > 0.0 ? run::kChoiceShare * config.timeBudget
                                                   : std::numeric_limits<double>::infinity();
  progress.preparing(fmt::format(
      "choosing the learner's settings on the task: {} alternatives{}, each training the "
      "original variables and no learning on {} seeds{}{}",
      run::learnerCandidates(config).size(),
      config.learnerFallbacks.empty()
          ? std::string()
          : fmt::format(" ({} more where none learns)", config.learnerFallbacks.size()),
      config.choiceSeeds,
      config.choiceRandomSets > 0
          ? fmt::format(" and {} random feature sets on 3", config.choiceRandomSets)
          : std::string(),
      config.timeBudget > 0.0 ? fmt::format(", within {:.0f} s of the budget", allowance)
                              : std::string()));
  const auto choice =
      run::chooseLearnerSettings(config, runner, allowance, options.threads, refuseFromPrediction);
  progress.preparedRun(run::learnerChoiceText(choice));
  if (choice.nothingLearns) {
    throw InputError(run::nothingLearnsText(choice), "learner.choose (" + config.env + ")");
  }
  options.learnerChoiceJson = run::learnerChoiceJson(choice);
  spent.choice = choice.seconds;
  spent.choiceFirst = choice.firstSeconds;
  spent.choiceFirstPredicted = choice.firstPredicted;
  return run::withLearnerChoice(config, choice);
}

// Sizes `config` to its time budget (run/time_budget.hpp), measuring as the run will evaluate,
// `spent` of it gone already; says what it chose and records it for run.json.
run::ExperimentConfig sizeToBudget(const run::ExperimentConfig& config, int runs,
                                   const run::BudgetSpent& spent, run::DiscoveryOptions& options,
                                   double& perRunSeconds, EvolveProgress& progress) {
  const std::string where = kBudgetWhere;
  double left = config.timeBudget - spent.choice;
  if (spent.choice > 0.0 && (left <= 0.0 || spent.choiceFirstPredicted)) {
    // The choice took the whole budget, or found one training longer than its share: refused
    // now where the measurement and the smallest run do not fit, predicted from its first
    // training, not after one training more (Swimmer-v5 on a loaded machine: 189 s, then 171 s
    // more, of 180).
    const double one = run::trialSecondsFrom(config, spent.choiceFirst, choiceBudget(config));
    run::refuseBeforeMeasuring(config, one, options.threads, left, spent, where, runs, true);
  }
  progress.preparing(
      fmt::format("measuring what an evaluation and a training cost here (at least {:.0f} s)",
                  std::ceil(run::kMeasureShare * config.timeBudget)));
  const double one = run::timeOneTraining(config, options);
  left -= one;
  run::refuseBeforeMeasuring(config, one, options.threads, left, spent, where, runs);
  const auto costs = run::measureCosts(config, options, run::kMeasureShare * config.timeBudget,
                                       run::kMeasureMaxShare * config.timeBudget);
  const auto sizes =
      run::sizeToBudget(config, costs, (left - costs.seconds) / runs, where, runs, spent);
  progress.preparedRun(run::budgetText(config.timeBudget, costs, sizes, runs));
  options.timeBudgetJson = run::budgetJson(config.timeBudget, costs, sizes);
  // Run r of a set ends by r shares of the budget after the measurement.
  perRunSeconds = (left - costs.seconds) / runs;
  options.deadline = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(perRunSeconds));
  options.finishSeconds = sizes.finishSeconds;
  options.finishTrainings = sizes.finishTrainings;
  return run::withSizes(config, sizes);
}

EvolveResult resume(const EvolveRequest& request, run::DiscoveryOptions options,
                    EvolveProgress& progress, const std::atomic<bool>& stop) {
  const std::string& dir = request.resume;
  if (!request.overrides.empty() || request.runs || request.out.dir) {
    throw InputError(
        "a resumed run continues with its stored config: only the number of generations and "
        "of threads may be given",
        "resume " + dir);
  }
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError("no such results directory", "resume " + dir);
  const auto expected = expectedConfig(request, dir);
  const DirectoryLock lock = lockDirectory(dir);
  options.outDir = dir;
  const std::string runsJson = dir + "/runs.json";
  if (fs::exists(runsJson)) {
    std::uint64_t seed = 0;
    int runs = 0;
    run::parseRunsJson(readFile(runsJson), runsJson, seed, runs);
    const std::string configPath = dir + "/config.toml";
    const auto base = run::loadStoredExperimentConfig(configPath);
    // Compared in today's form: keys added since the runs were written read as their defaults.
    if (expected && run::formatExperimentConfig(*expected) != run::formatExperimentConfig(base)) {
      throw InputError(
          "the config differs from the one the runs were started with (see " + configPath + ")",
          dir);
    }
    return runSet(base, runs, options, request.generations, progress, stop);
  }
  if (!fs::exists(dir + "/config.toml")) {
    throw InputError("no run to resume (neither checkpoint.json nor config.toml)", dir);
  }
  const auto discovery = openRun(expected, options, request.generations);
  if (discovery->finished()) {
    progress.alreadyComplete(dir, discovery->config().gp.generations);
    return {dir, true, {run::outcomeOf(*discovery, 1)}};
  }
  EvolveResult result{dir, false, {}};
  result.finished = runOne(*discovery, dir, "", 1, dir, progress, stop);
  if (result.finished) result.outcomes.push_back(run::outcomeOf(*discovery, 1));
  return result;
}

// Starts (or continues: openRun) the single run of `config` in the directory claimed by `lock`
// and runs it. One that fails (or is interrupted) before its first generation ends leaves no
// directory that the call created.
EvolveResult runSingle(const run::ExperimentConfig& config, const run::DiscoveryOptions& options,
                       DirectoryLock& lock, EvolveProgress& progress,
                       const std::atomic<bool>& stop) {
  std::unique_ptr<run::Discovery> discovery;
  try {
    discovery = openRun(config, options, std::nullopt);
  } catch (...) {
    lock.removeCreatedDirectory();  // Nothing half-made is left behind.
    throw;
  }
  EvolveResult result{options.outDir, false, {}};
  try {
    result.finished = runOne(*discovery, options.outDir, "", 1, options.outDir, progress, stop);
  } catch (...) {
    // Stopped (an error, an interruption) before its first generation ended: nothing to keep.
    if (discovery->history().empty()) lock.removeCreatedDirectory();
    throw;
  }
  if (result.finished) result.outcomes.push_back(run::outcomeOf(*discovery, 1));
  return result;
}

// A fresh run with the config, sizes and learner settings of the finished run in
// request.replay, its run.json's measurement and choice copied (run/replay.hpp).
EvolveResult replay(const EvolveRequest& request, run::DiscoveryOptions options,
                    EvolveProgress& progress, const std::atomic<bool>& stop) {
  const std::string& dir = request.replay;
  if (!request.config.empty() || !request.overrides.empty() || request.runs ||
      request.generations || !request.resume.empty()) {
    throw InputError(
        "a replay runs the stored config and sizes again: only the threads (or workers) and the "
        "results directory may be given",
        "replay " + dir);
  }
  const auto source = run::readFinishedRun(dir, kVersion);
  const run::ExperimentConfig& config = source.config;
  options.learnerChoiceJson = source.learnerChoiceJson;
  options.timeBudgetJson = source.timeBudgetJson;
  if (options.envJson.empty()) options.envJson = source.envJson;
  options.replayOf = fs::absolute(dir).lexically_normal().string();
  std::string name = fs::path(dir).lexically_normal().filename().string();
  if (name.empty()) name = fs::path(dir).lexically_normal().parent_path().filename().string();
  name = request.outName.empty() ? name + "-replay" : request.outName;
  if (!run::isRunName(name)) name = config.name + "-replay";
  progress.preparedRun(fmt::format(
      "replaying {}: population {}, generations {}, validation {} candidates x {} seeds, "
      "confirmation {} seeds{}, as the run used them\n",
      dir, config.gp.population, config.gp.generations, config.validation.candidates,
      config.validation.seeds, config.validation.confirmSeeds,
      source.sizesFromClock ? " (chosen by its time budget)" : ""));
  DirectoryLock lock = claimResultsDirectory(request.out, name, run::refuseExistingRuns);
  options.outDir = lock.directory();
  return runSingle(config, options, lock, progress, stop);
}

}  // namespace

// The run in options.outDir: resumed from its checkpoint once it has been started there
// (config.toml; it must have been started with `config` when given), else started with `config`.
std::unique_ptr<run::Discovery> openRun(const std::optional<run::ExperimentConfig>& config,
                                        const run::DiscoveryOptions& options,
                                        std::optional<int> generations) {
  if (!config || fs::exists(options.outDir + "/config.toml")) {
    return run::Discovery::resume(options, config, generations);
  }
  run::ExperimentConfig fresh = *config;
  if (generations) fresh.gp.generations = *generations;
  return run::Discovery::start(fresh, options);
}

EvolveResult evolve(const EvolveRequest& request, EvolveProgress& progress,
                    const std::atomic<bool>& stop) {
  run::DiscoveryOptions options;
  options.threads = request.makeEvaluator ? request.threads : usableThreads(request.threads);
  options.version = kVersion;
  options.revision = kRevision;
  options.makeEvaluator = request.makeEvaluator;
  options.trialRunner = request.trialRunner;
  options.processes = request.processes;
  options.envJson = request.envJson;
  if (!request.replay.empty()) return replay(request, options, progress, stop);
  if (!request.resume.empty()) return resume(request, options, progress, stop);

  auto overrides = request.overrides;
  if (request.generations) {
    overrides.push_back("gp.generations=" + std::to_string(*request.generations));
  }
  auto config = loadConfig(request.config, overrides);
  // Sizes given (the generations, gp.population, gp.generations) replace a time budget that
  // comes from the config (user-env's default), unless the budget is given too.
  if (givesSizes(request) && !givesKey(overrides, "time_budget")) config.timeBudget = 0.0;
  const int runs = request.runs.value_or(1);
  run::BudgetSpent spent;  // What choosing the learner's settings took.
  spent.budget = config.timeBudget;
  double perRunSeconds = 0.0;  // A time budget's share of each run.
  if (config.timeBudget > 0.0 && options.processes > 1) {
    throw InputError("a time budget is not measured under MPI: give the sizes instead",
                     kBudgetWhere);
  }
  if (run::choosesLearner(config)) config = chooseLearner(config, runs, options, spent, progress);
  if (config.timeBudget > 0.0) {
    config = sizeToBudget(config, runs, spent, options, perRunSeconds, progress);
  }
  // Parents and offspring with every genome at its size limits.
  requireMemory(2.0 * config.gp.population * config.limits.maxFeatures * config.limits.maxSize *
                    static_cast<double>(sizeof(expr::Node)),
                "the population at its genome size limits",
                "gp.population x genome.max_features x genome.max_size");
  const std::string& name = request.outName.empty() ? config.name : request.outName;
  if (!run::isRunName(name)) {
    throw InputError(
        "a results directory's name must be letters, digits, '.', '_' and '-', "
        "not starting with '.'",
        name);
  }
  // A directory holding a run or a set is resumed, never started over, even with force.
  DirectoryLock lock = claimResultsDirectory(request.out, name, run::refuseExistingRuns);
  options.outDir = lock.directory();
  if (runs == 1) return runSingle(config, options, lock, progress, stop);
  run::validate(config);
  createDirectories(options.outDir, "results directory");
  writeFileAtomically(options.outDir + "/config.toml", run::formatExperimentConfig(config));
  writeFileAtomically(options.outDir + "/runs.json", run::formatRunsJson(config.seed, runs));
  return runSet(config, runs, options, std::nullopt, progress, stop, perRunSeconds);
}

}  // namespace gpfd::service
