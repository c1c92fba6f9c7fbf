#include "gpfd/service/assess.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <stdexcept>

#include "gpfd/env/environment.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/learner_choice.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/feature_source.hpp"
#include "gpfd/service/params.hpp"
#include "gpfd/service/resources.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"

namespace gpfd::service {
namespace {

// The name of the no-learning reference's row (a policy that cannot depend on the state).
constexpr const char* kNoLearning = "no-learning";

// The config of an assessment: the given config's learner (or the environment's default), its
// params routed to the environment or the long budget.
run::ExperimentConfig assessConfig(const AssessRequest& r) {
  run::ExperimentConfig config;
  if (!r.config.empty()) {
    config = loadConfig(r.config, r.overrides);
    if (!r.env.empty() && r.env != config.env) {
      throw InputError("the environment differs from the config's (" + config.env + ")", r.env);
    }
  } else {
    if (r.env.empty()) throw InputError("give an environment or a config", r.where);
    if (!r.overrides.empty()) throw InputError("config overrides need a config", r.where);
    config.env = r.env;
    config.learner = env::Registry::global().info(r.env).defaultLearner;
  }
  const auto routed = routeParams(r.params, env::Registry::global().info(config.env), "--param");
  for (const auto& [key, value] : routed.env) config.envParams[key] = value;
  for (const auto& [key, value] : routed.learner) config.assessParams[key] = value;
  const auto& learner = rl::LearnerRegistry::global().info(config.learner);
  // A learner setting given wins over its choice, as an override does in gpfd evolve; the
  // budget is the assessment's length, never a choice's.
  Params given = routed.learner;
  given.erase(learner.budgetParam);
  run::keepChoicesWith(config, given);
  if (r.budget > 0) config.assessParams[learner.budgetParam] = std::to_string(r.budget);
  if (r.runs > 0) config.assessRuns = r.runs;
  config.seed = r.seed;
  run::validate(config);
  return config;
}

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

// The sets to assess, the original variables first (the baseline).
std::vector<run::FeatureSet> featureSets(const AssessRequest& r, const run::LearningTask& task) {
  const bool asEvolved = task.config().withOriginal;
  std::vector<run::FeatureSet> sets;
  if (r.raw || !r.features.empty()) sets.push_back({"original", run::TrialFeatures::original()});
  for (const auto& source : r.features) {
    const auto file = featuresFor(source, task);
    std::string name =
        source.name.empty() ? std::filesystem::path(source.path).stem().string() : source.name;
    for (const auto& s : sets) {
      // append, not +: GCC 12 gives a false -Wrestrict on "-" + std::string (GCC bug 105329).
      if (s.name == name || name == kNoLearning) {
        name.append("-").append(std::to_string(sets.size()));
      }
    }
    // Compiled once here, so that a genome past the compiler's limits is the user's input, named
    // as such, before anything is written.
    const auto setOf = [&](bool withOriginal) {
      auto features = run::TrialFeatures::ofGenome(file.genome, withOriginal);
      try {
        features.map(task);
      } catch (const std::invalid_argument& e) {
        throw InputError(e.what(), source.path.empty() ? source.name : source.path);
      }
      return features;
    };
    // Assessed as GP evaluated them: with the original variables appended when the config's
    // fitness.with_original says so; withOriginal adds that variant as a further set.
    sets.push_back({name + (asEvolved ? "+original" : ""), setOf(asEvolved)});
    if (r.withOriginal && !asEvolved) sets.push_back({name + "+original", setOf(true)});
  }
  if (r.fourier > 0) sets.push_back(run::fourierFeatureSet(task, r.fourier));
  if (sets.empty())
    throw InputError("nothing to assess: give features or the raw variables", r.where);
  // The no-learning reference, last: runs seeded (seed, its index, run), leaving every other
  // set's seeds as they are.
  sets.push_back({kNoLearning, run::TrialFeatures::noLearning()});
  return sets;
}

// An assessment already in the directory is replaced only when forced.
void refuseAssessment(const OutputChoice& out, const std::string& dir) {
  if (!out.force && std::filesystem::exists(dir + "/summary.csv")) {
    throw InputError(fmt::format("the directory already holds an assessment; pass {} to replace "
                                 "it, or choose another {}",
                                 out.flag == "out" ? "force=True" : "--force", out.flag),
                     dir);
  }
}

}  // namespace

AssessResult assess(const AssessRequest& r, const TextSink& print) {
  AssessResult result;
  result.config = assessConfig(r);
  const auto& config = result.config;
  // Every input is read and checked before anything is trained or written (the sets do not
  // depend on the learner's settings).
  const auto sets =
      featureSets(r, run::LearningTask(config, run::LearningTask::Budget::Assessment));
  // Every run's curve is kept until the statistics are computed.
  requireMemory(static_cast<double>(sets.size()) * config.assessRuns *
                    static_cast<double>(runBudget(config) + 1) * sizeof(rl::CurvePoint),
                "the learning curves of every run", "--runs, --budget");
  std::optional<DirectoryLock> lock;
  if (r.write) {
    lock.emplace(claimResultsDirectory(
        r.out, "assess-" + config.env,
        [&](const std::string& dir) { refuseAssessment(r.out, dir); }, "output directory"));
    result.dir = lock->directory();
  }
  run::ThreadTrialRunner threads(usableThreads(r.threads));
  run::TrialRunner& runner = r.trialRunner ? *r.trialRunner : threads;
  // The learner's settings of learner.choose, chosen as gpfd evolve chooses them (the same
  // config and seed choose the same).
  std::optional<run::LearnerChoice> choice;
  if (run::choosesLearner(config)) {
    choice = run::chooseLearnerSettings(config, runner);
    result.config = run::withLearnerChoice(config, *choice);
    if (print) print(run::learnerChoiceText(*choice));
  }
  const run::LearningTask task(config, run::LearningTask::Budget::Assessment);
  if (print) {
    print(fmt::format("gpfd assess: {} feature sets x {} runs on {} ({}), seed {}\n", sets.size(),
                      config.assessRuns, config.env, config.learner, config.seed));
  }
  const auto runs = run::runAssessment(task, sets, config.assessRuns, config.seed, runner);
  result.summary = run::summarizeAssessment(runs, 0);
  result.runs = static_cast<long>(sets.size()) * config.assessRuns;
  if (lock) {
    run::writeAssessment(result.dir, runs, result.summary, config.env + ": " + config.learner,
                         rl::LearnerRegistry::global().info(config.learner).rowName);
    if (choice) {
      writeFileAtomically(result.dir + "/learner_choice.json",
                          run::learnerChoiceJson(*choice) + "\n");
    }
  }
  for (const auto& row : result.summary) result.diverged += row.diverged;
  if (print) {
    for (const auto& row : result.summary) {
      print(fmt::format(
          "{:<24} final {:.6g} ± {:.3g} (Welch p {:.3g}, Mann-Whitney p {:.3g}, d {:.3g})  area "
          "{:.6g} (Welch p {:.3g})\n",
          row.name, row.final.mean, row.final.halfWidth, row.vsBaseline.welchP,
          row.vsBaseline.mannWhitneyP, row.vsBaseline.cohenD, row.area.mean,
          row.areaVsBaseline.welchP));
    }
    if (lock) print(fmt::format("results in {}\n", result.dir));
  }
  return result;
}

}  // namespace gpfd::service
