#include "gpfd/run/time_budget.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "gpfd/gp/init.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/thread_evaluator.hpp"
#include "gpfd/run/trial_runner.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/number.hpp"

namespace gpfd::run {
namespace {

// The measurement's seeds: a stream of their own, which no run draws from.
constexpr std::uint64_t kMeasureStream = 0x425544;

template <typename Work>
double wallSeconds(const Work& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

expr::Genome variablesGenome(std::size_t dim) {
  expr::Genome genome;
  for (std::size_t i = 0; i < dim; ++i) {
    const expr::Node variable = expr::Node::variable(static_cast<int>(i));
    genome.addFeature(expr::TreeView(&variable, 1));
  }
  return genome;
}

// Environment steps per episode of the curves, over their rows from `from` (a share of each
// curve) on; 0 when they played none.
double stepsPerEpisode(const std::vector<rl::LearningCurve>& curves, double from) {
  double steps = 0.0, episodes = 0.0;
  for (const auto& curve : curves) {
    if (curve.points.empty()) continue;
    const auto first = static_cast<std::size_t>(from * static_cast<double>(curve.points.size()));
    const auto& last = curve.points.back();
    const rl::CurvePoint before = first == 0 ? rl::CurvePoint{} : curve.points[first - 1];
    steps += static_cast<double>(last.steps - before.steps);
    episodes += static_cast<double>(last.episodes - before.episodes);
  }
  return episodes > 0.0 ? steps / episodes : 0.0;
}

// The learner's budget parameter (LearnerInfo::budgetParam: pg's updates) under `budget`; 0 where
// the learner has none or it is not a number.
double budgetUnits(const ExperimentConfig& config, LearningTask::Budget budget) {
  const auto& info = rl::LearnerRegistry::global().info(config.learner);
  const std::string& key = info.budgetParam;
  std::string value;
  for (const auto& spec : info.params) {
    if (spec.name == key) value = spec.defaultValue;
  }
  const auto take = [&](const std::map<std::string, std::string>& params) {
    if (const auto it = params.find(key); it != params.end()) value = it->second;
  };
  take(config.learnerParams);
  if (budget == LearningTask::Budget::Validation) take(config.validation.params);
  if (budget == LearningTask::Budget::Confirmation) take(config.validation.confirmParams);
  try {
    return key.empty() || value.empty() ? 0.0 : parseNumber(value, key);
  } catch (const InputError&) {
    return 0.0;
  }
}

// Validation and confirmation, in wall seconds, at the given sizes.
double validationSeconds(const CostMeasure& c, int candidates, int seeds) {
  return seeds * ((candidates + 1) * c.validationRun + c.noLearningValidation);
}
double confirmationSeconds(const CostMeasure& c, int confirmSeeds) {
  // The winner and the original variables, both at the original variables' cost, and no
  // learning; every seed (an early end only saves).
  return confirmSeeds * (2 * c.confirmationRun + c.noLearningConfirmation);
}
double gpSeconds(const CostMeasure& c, int population, int generations) {
  return population * c.randomEvaluation +
         (generations - 1) * population * kFreshShare * c.learnedEvaluation +
         generations * population * c.rungEvaluations;
}

}  // namespace

CostMeasure measureCosts(const ExperimentConfig& config, const DiscoveryOptions& options,
                         double minSeconds, double maxSeconds) {
  CostMeasure costs;
  const auto start = std::chrono::steady_clock::now();
  const LearningTask task(config, LearningTask::Budget::Trial);
  std::unique_ptr<gp::Evaluator> evaluator;
  int workers = options.threads;
  if (options.makeEvaluator) {
    evaluator = options.makeEvaluator({config, formatExperimentConfig(config), [] {}});
  } else {
    auto threads = std::make_unique<ThreadEvaluator>(
        [&task](const expr::Genome& g, Rng& rng) { return trialFitness(task, g, rng); },
        options.threads);
    workers = threads->threads();
    evaluator = std::move(threads);
  }
  workers = std::max(1, workers);
  const auto seedAt = [&](std::uint64_t kind, int i) {
    return deriveSeed(config.seed, kMeasureStream, kind, static_cast<std::uint64_t>(i));
  };
  // Rounds of random genomes as generation 0 makes them, four per worker, and of the original
  // variables as a genome, two per worker, until `minSeconds` have passed (at least one round),
  // so that the load of a shared machine is averaged over a while.
  const auto space = searchSpace(config, static_cast<int>(task.stateDim()));
  const auto variables = variablesGenome(task.stateDim());
  // Wall seconds of the original variables evaluated two per worker by `on`, seeds of `kind`
  // from `first` on.
  const auto variablesRound = [&](gp::Evaluator& on, std::uint64_t kind, int first) {
    const std::vector<const expr::Genome*> pointers(static_cast<std::size_t>(2 * workers),
                                                    &variables);
    std::vector<std::uint64_t> seeds;
    for (int i = 0; i < 2 * workers; ++i) seeds.push_back(seedAt(kind, first + i));
    return wallSeconds([&] { on.evaluate(pointers, seeds); });
  };
  double randomSeconds = 0.0, variablesSeconds = 0.0;
  int rounds = 0;
  do {
    std::vector<expr::Genome> randoms;
    std::vector<const expr::Genome*> pointers;
    std::vector<std::uint64_t> seeds;
    Rng rng(seedAt(0, rounds));
    for (int i = 0; i < 4 * workers; ++i) randoms.push_back(gp::randomGenome(rng, space));
    for (int i = 0; i < 4 * workers; ++i) {
      pointers.push_back(&randoms[static_cast<std::size_t>(i)]);
      seeds.push_back(seedAt(1, rounds * 4 * workers + i));
    }
    randomSeconds += wallSeconds([&] { evaluator->evaluate(pointers, seeds); });
    variablesSeconds += variablesRound(*evaluator, 2, rounds * 2 * workers);
    ++rounds;
  } while (randomSeconds + variablesSeconds < minSeconds);
  costs.randomEvaluation = randomSeconds / (4.0 * workers * rounds);
  const double variablesEvaluation = variablesSeconds / (2.0 * workers * rounds);
  // Trainings of the trial, validation and confirmation, two per worker; their curves.
  ThreadTrialRunner threads(options.threads);
  TrialRunner& runner = options.trialRunner ? *options.trialRunner : threads;
  std::vector<rl::LearningCurve> curves;
  const auto perRun = [&](LearningTask::Budget budget, const TrialFeatures& set,
                          std::uint64_t kind) {
    const LearningTask trained(config, budget);
    TrialBatch batch{{set}, {{}}};
    for (int i = 0; i < 2 * workers; ++i) batch.seeds[0].push_back(seedAt(kind, i));
    const double seconds = wallSeconds([&] { curves = runner.run(trained, batch, {})[0]; });
    return seconds / (2.0 * workers);
  };
  // Successive halving's rungs: the original variables' evaluation at each, two per worker.
  const auto rungs = makeRungEvaluators(config, options);
  for (std::size_t r = 0; r < rungs.size(); ++r) {
    const double each = variablesRound(*rungs[r], 8 + r, 0) / (2.0 * workers);
    costs.rungEvaluations += std::pow(config.gp.promote, static_cast<double>(r + 1)) * each;
  }
  const double trialRun = perRun(LearningTask::Budget::Trial, TrialFeatures::original(), 7);
  const double trialSteps = stepsPerEpisode(curves, 0.0);
  double endSteps = stepsPerEpisode(curves, 0.75);
  // Validation's and confirmation's trainings as long as the trial's, scaled by their budgets
  // (learner's budget parameter); measured where that fits `maxSeconds`, else estimated so.
  const double trialUnits = budgetUnits(config, LearningTask::Budget::Trial);
  // A longer training's part past the trial's length plays episodes as long as the trial's last
  // quarter did.
  const double lateGrowth = trialSteps > 0.0 ? std::max(1.0, endSteps / trialSteps) : 1.0;
  const auto scaled = [&](LearningTask::Budget budget) {
    const double units = budgetUnits(config, budget);
    if (trialUnits <= 0.0 || units <= 0.0) return trialRun;
    const double ratio = units / trialUnits;
    return trialRun * (ratio <= 1.0 ? ratio : 1.0 + (ratio - 1.0) * lateGrowth);
  };
  const double validationGuess = scaled(LearningTask::Budget::Validation);
  const double confirmationGuess =
      config.validation.confirms() ? scaled(LearningTask::Budget::Confirmation) : 0.0;
  // Each measured kind takes a round of 2 per worker, with and without learning.
  const double measuring = 2.0 * workers * 2.0 * (validationGuess + confirmationGuess);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (config.validation.candidates > 0 && elapsed + measuring > maxSeconds) {
    costs.estimated = true;
    costs.validationRun = costs.noLearningValidation = validationGuess;
    costs.confirmationRun = costs.noLearningConfirmation = confirmationGuess;
  } else if (config.validation.candidates > 0) {
    costs.validationRun = perRun(LearningTask::Budget::Validation, TrialFeatures::original(), 3);
    costs.noLearningValidation =
        perRun(LearningTask::Budget::Validation, TrialFeatures::noLearning(), 4);
    if (config.validation.confirms()) {
      costs.confirmationRun =
          perRun(LearningTask::Budget::Confirmation, TrialFeatures::original(), 5);
      endSteps = std::max(endSteps, stepsPerEpisode(curves, 0.75));
      costs.noLearningConfirmation =
          perRun(LearningTask::Budget::Confirmation, TrialFeatures::noLearning(), 6);
    }
  }
  // Later generations' sets learn as the original variables do by the end of a longer training,
  // so their episodes last longer (or shorter) than over a trial of the original variables:
  // halfway between the two, as steps per episode go.
  costs.growth = trialSteps > 0.0 && endSteps > 0.0 ? endSteps / trialSteps : 1.0;
  costs.learnedEvaluation =
      std::max(costs.randomEvaluation, variablesEvaluation * (1.0 + costs.growth) / 2.0);
  costs.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return costs;
}

double timeOneTraining(const ExperimentConfig& config, const DiscoveryOptions& options) {
  ThreadTrialRunner threads(1);
  TrialRunner& runner = options.trialRunner ? *options.trialRunner : threads;
  const LearningTask task(config, LearningTask::Budget::Trial);
  const TrialBatch batch{{TrialFeatures::original()},
                         {{deriveSeed(config.seed, kMeasureStream, 9)}}};
  return wallSeconds([&] { runner.run(task, batch, {}); });
}

double trialSecondsFrom(const ExperimentConfig& config, double seconds,
                        LearningTask::Budget budget) {
  const double trial = budgetUnits(config, LearningTask::Budget::Trial);
  const double units = budgetUnits(config, budget);
  return trial > 0.0 && units > 0.0 ? seconds * trial / units : seconds;
}

void refuseBeforeMeasuring(const ExperimentConfig& config, double oneTraining, int workers,
                           double seconds, const BudgetSpent& spent, const std::string& where,
                           int runs, bool predictedTraining) {
  const double each = oneTraining / std::max(1, workers);
  // The measurement's first round (four random genomes and two of the original variables per
  // worker, fitness.trials trainings each) and its trial trainings, all at the original
  // variables' cost, one after another on each worker.
  const double measuring = oneTraining * (6.0 * config.trials + 2.0);
  // The smallest run: population kMinPopulation, 2 generations (the second kFreshShare new), and
  // validation and confirmation at their smallest, spread over the workers.
  const auto& v = config.validation;
  const auto ratio = [&](LearningTask::Budget budget) {
    const double trial = budgetUnits(config, LearningTask::Budget::Trial);
    const double units = budgetUnits(config, budget);
    return trial > 0.0 && units > 0.0 ? units / trial : 1.0;
  };
  double trainings = (1.0 + kFreshShare) * kMinPopulation * config.trials;
  if (v.candidates > 0) {
    trainings += std::min(v.seeds, 10) * (std::min(v.candidates, 3) + 2) *
                 ratio(LearningTask::Budget::Validation);
    if (v.confirms()) {
      trainings += std::min(v.confirmSeeds, std::max(10, 2 * v.confirmLooks)) * 3 *
                   ratio(LearningTask::Budget::Confirmation);
    }
  }
  const double least = trainings * each;
  if (measuring + least * runs <= seconds) return;
  CostMeasure predicted;
  predicted.seconds = oneTraining + measuring;
  throw InputError(
      fmt::format("{:.0f} s{} is too short here: one training of the original variables {} "
                  "{:.1f} s, so measuring what an evaluation costs would take about {:.0f} s and "
                  "the smallest run (population {}, 2 generations, the smallest validation) about "
                  "{:.0f} s{}; give at least {:.0f} s{}, or the sizes",
                  spent.budget, runs > 1 ? fmt::format(" for {} runs", runs) : "",
                  predictedTraining ? "would take about" : "took", oneTraining, measuring,
                  kMinPopulation, least,
                  runs > 1 ? fmt::format(", {} runs about {:.0f} s", runs, least * runs) : "",
                  sufficientBudget(predicted, least * runs, spent), runs > 1 ? ", fewer runs" : ""),
      where);
}

double finishSeconds(const ExperimentConfig& config, const CostMeasure& costs,
                     const BudgetSizes& sizes) {
  if (config.validation.candidates == 0) return 0.0;
  return validationSeconds(costs, sizes.candidates, sizes.seeds) +
         (config.validation.confirms() ? confirmationSeconds(costs, sizes.confirmSeeds) : 0.0);
}

double sufficientBudget(const CostMeasure& costs, double runsSeconds, const BudgetSpent& spent) {
  // At a budget B the choice takes its first trainings, or at most kChoiceShare B (more only by
  // what its prediction missed), the measurement about what it took here and kMeasureShare B
  // more: B must hold those and the runs, with a margin for a loaded machine (one training took 7.0
  // s, then 10.4 s on Acrobot-v1 in Python minutes apart: docs/results/budget-call/).
  constexpr double kMargin = 1.5;
  const double fixed = costs.seconds + runsSeconds;
  double least = (spent.choiceFirst + fixed) / (1.0 - kMeasureShare);
  if (spent.choice > 0.0) least = std::max(least, fixed / (1.0 - kChoiceShare - kMeasureShare));
  return 10.0 * std::ceil(kMargin * least / 10.0);
}

BudgetSizes sizeToBudget(const ExperimentConfig& config, const CostMeasure& costs, double seconds,
                         const std::string& where, int runs, const BudgetSpent& spent) {
  const auto& v = config.validation;
  BudgetSizes sizes{0, 0, v.candidates, v.seeds, v.confirmSeeds, 0.0, 0.0, 0.0};
  // Validation and confirmation: the config's sizes, shrunk to their share when they exceed it.
  const double share = kValidationShare * seconds;
  if (finishSeconds(config, costs, sizes) > share) {
    const double f = share / finishSeconds(config, costs, sizes);
    const auto shrink = [f](int n, int least) {
      return std::min(n, std::max(least, static_cast<int>(std::floor(n * f))));
    };
    sizes.candidates = shrink(v.candidates, 3);
    sizes.seeds = shrink(v.seeds, 10);
    if (v.confirms()) sizes.confirmSeeds = shrink(v.confirmSeeds, std::max(10, 2 * v.confirmLooks));
  }
  sizes.finishSeconds = finishSeconds(config, costs, sizes);
  if (config.validation.candidates > 0) {
    // The sets, the original variables and no learning on each seed; the winner, the original
    // variables and no learning on each confirmation seed; each as long as its budget says.
    const auto ratio = [&](LearningTask::Budget budget) {
      const double trial = budgetUnits(config, LearningTask::Budget::Trial);
      const double units = budgetUnits(config, budget);
      return trial > 0.0 && units > 0.0 ? units / trial : 1.0;
    };
    sizes.finishTrainings =
        sizes.seeds * (sizes.candidates + 2) * ratio(LearningTask::Budget::Validation);
    if (config.validation.confirms()) {
      sizes.finishTrainings += sizes.confirmSeeds * 3 * ratio(LearningTask::Budget::Confirmation);
    }
  }
  // GP: the population P from P = kRatio G and P r + (G - 1) P u l = the rest (r, l: a random and
  // a learned evaluation; u: kFreshShare); the generations G that then fill the rest, which
  // the run fits to its deadline after each generation (DiscoveryOptions::deadline).
  const double rest = seconds - sizes.finishSeconds;
  // With successive halving every generation's rungs add to both r and u l.
  const double first = costs.randomEvaluation + costs.rungEvaluations;
  const double later = kFreshShare * costs.learnedEvaluation + costs.rungEvaluations;
  const double a = later / kRatio;
  const double b = first - later;
  const double population =
      a > 0.0 ? (-b + std::sqrt(b * b + 4.0 * a * std::max(0.0, rest))) / (2 * a) : 0.0;
  sizes.population = std::max(kMinPopulation, static_cast<int>(std::floor(population)));
  const double perGeneration = sizes.population * later;
  const double after = rest - sizes.population * first;
  const int expected = perGeneration > 0.0
                           ? 1 + static_cast<int>(std::floor(std::max(0.0, after) / perGeneration))
                           : 2;
  sizes.generations = expected;
  sizes.predictedSeconds = gpSeconds(costs, sizes.population, expected) + sizes.finishSeconds;
  if (expected < 2) {
    const double least = gpSeconds(costs, kMinPopulation, 2) + sizes.finishSeconds;
    const std::string smallest = fmt::format(
        "the smallest run (population {}, 2 generations, {} candidates x {} validation seeds, {} "
        "confirmation seeds) takes about {:.0f} s{}",
        kMinPopulation, sizes.candidates, sizes.seeds, sizes.confirmSeeds, least,
        runs > 1 ? fmt::format(", so {} runs about {:.0f} s", runs, least * runs) : "");
    const std::string before =
        spent.choice > 0.0
            ? fmt::format("{:.1f} s choosing the learner's settings and ", spent.choice)
            : std::string();
    throw InputError(
        fmt::format("{:.0f} s{} is too short here: {}, after {}{:.1f} s of measuring what an "
                    "evaluation costs; give at least {:.0f} s{}, or the sizes",
                    spent.budget, runs > 1 ? fmt::format(" for {} runs", runs) : "", smallest,
                    before, costs.seconds, sufficientBudget(costs, least * runs, spent),
                    runs > 1 ? ", fewer runs" : ""),
        where);
  }
  return sizes;
}

ExperimentConfig withSizes(ExperimentConfig config, const BudgetSizes& sizes) {
  config.gp.population = sizes.population;
  config.gp.generations = sizes.generations;
  config.validation.candidates = sizes.candidates;
  config.validation.seeds = sizes.seeds;
  config.validation.confirmSeeds = sizes.confirmSeeds;
  config.timeBudget = 0.0;
  return config;
}

std::string budgetJson(double budget, const CostMeasure& costs, const BudgetSizes& sizes) {
  nlohmann::ordered_json j{{"seconds", budget},
                           {"measured",
                            {{"seconds", costs.seconds},
                             {"random_evaluation", costs.randomEvaluation},
                             {"learned_evaluation", costs.learnedEvaluation},
                             {"episode_growth", costs.growth},
                             {"validation_run", costs.validationRun},
                             {"confirmation_run", costs.confirmationRun},
                             {"no_learning_validation_run", costs.noLearningValidation},
                             {"no_learning_confirmation_run", costs.noLearningConfirmation}}},
                           {"chosen",
                            {{"population", sizes.population},
                             {"generations", sizes.generations},
                             {"candidates", sizes.candidates},
                             {"seeds", sizes.seeds},
                             {"confirm_seeds", sizes.confirmSeeds},
                             {"predicted_seconds_per_run", sizes.predictedSeconds},
                             {"validation_and_confirmation_seconds", sizes.finishSeconds}}}};
  if (costs.rungEvaluations > 0) j["measured"]["rung_evaluations"] = costs.rungEvaluations;
  if (costs.estimated) j["measured"]["trainings_estimated_from_the_trial"] = true;
  return j.dump();
}

std::string budgetText(double budget, const CostMeasure& costs, const BudgetSizes& sizes,
                       int runs) {
  return fmt::format(
      "time budget {:.0f} s: an evaluation costs {:.3g} s (random genome) to {:.3g} s (the "
      "original variables), a validation training {:.3g} s, a confirmation training {:.3g} s on "
      "this machine (measured in {:.1f} s); chosen: population {}, generations {} (fitted to the "
      "budget after each generation), validation {} candidates x {} seeds, confirmation {} "
      "seeds{} (predicted {:.0f} s{}); written to config.toml. These sizes come from the clock: "
      "another call with the same seed may size the run differently; --replay DIR "
      "(gpfd.evolve(replay=DIR)) reruns this run exactly\n",
      budget, costs.randomEvaluation, costs.learnedEvaluation, costs.validationRun,
      costs.confirmationRun, costs.seconds, sizes.population, sizes.generations, sizes.candidates,
      sizes.seeds, sizes.confirmSeeds, runs > 1 ? fmt::format(" for each of {} runs", runs) : "",
      sizes.predictedSeconds, runs > 1 ? " per run" : "");
}

}  // namespace gpfd::run
