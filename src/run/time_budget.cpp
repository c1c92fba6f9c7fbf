#include "gpfd/run/time_budget.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "gpfd/gp/init.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/thread_evaluator.hpp"
#include "gpfd/run/trial_runner.hpp"
#include "gpfd/util/error.hpp"

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
                         double minSeconds) {
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
  perRun(LearningTask::Budget::Trial, TrialFeatures::original(), 7);
  const double trialSteps = stepsPerEpisode(curves, 0.0);
  double endSteps = stepsPerEpisode(curves, 0.75);
  if (config.validation.candidates > 0) {
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

double finishSeconds(const ExperimentConfig& config, const CostMeasure& costs,
                     const BudgetSizes& sizes) {
  if (config.validation.candidates == 0) return 0.0;
  return validationSeconds(costs, sizes.candidates, sizes.seeds) +
         (config.validation.confirms() ? confirmationSeconds(costs, sizes.confirmSeeds) : 0.0);
}

BudgetSizes sizeToBudget(const ExperimentConfig& config, const CostMeasure& costs, double seconds,
                         const std::string& where, int runs) {
  const auto& v = config.validation;
  BudgetSizes sizes{0, 0, v.candidates, v.seeds, v.confirmSeeds, 0.0, 0.0};
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
        "confirmation seeds) takes about {:.0f} s",
        kMinPopulation, sizes.candidates, sizes.seeds, sizes.confirmSeeds, least);
    const double total = seconds * runs + costs.seconds;
    const double needed = least * runs + costs.seconds;
    throw InputError(
        runs == 1
            ? fmt::format("{:.0f} s is too short here: {} after {:.1f} s of measuring what an "
                          "evaluation costs; give at least {:.0f} s, or the sizes",
                          total, smallest, costs.seconds, std::ceil(needed))
            : fmt::format("{:.0f} s for {} runs is too short here: {}, so {} runs take "
                          "about {:.0f} s with the {:.1f} s of measuring what an evaluation "
                          "costs; give at least {:.0f} s, fewer runs, or the sizes",
                          total, runs, smallest, runs, needed, costs.seconds, std::ceil(needed)),
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
  return j.dump();
}

std::string budgetText(double budget, const CostMeasure& costs, const BudgetSizes& sizes,
                       int runs) {
  return fmt::format(
      "time budget {:.0f} s: an evaluation costs {:.3g} s (random genome) to {:.3g} s (the "
      "original variables), a validation training {:.3g} s, a confirmation training {:.3g} s on "
      "this machine (measured in {:.1f} s); chosen: population {}, generations {} (fitted to the "
      "budget after each generation), validation {} candidates x {} seeds, confirmation {} "
      "seeds{} (predicted {:.0f} s{}); written to config.toml\n",
      budget, costs.randomEvaluation, costs.learnedEvaluation, costs.validationRun,
      costs.confirmationRun, costs.seconds, sizes.population, sizes.generations, sizes.candidates,
      sizes.seeds, sizes.confirmSeeds, runs > 1 ? fmt::format(" for each of {} runs", runs) : "",
      sizes.predictedSeconds, runs > 1 ? " per run" : "");
}

}  // namespace gpfd::run
