// run: a run sized to a time budget (`time_budget`, `gpfd evolve --time-budget 10m`,
// `gpfd.evolve(time_budget=600)`). What an evaluation and a training cost on this task and
// machine is measured first, on a few random genomes and on the original variables, spread over
// the run's workers as the run spreads them; the population, the generations and the validation
// are then chosen to fill the budget (docs/discovery.md, "A time budget"). The measured times
// reach the run only through the sizes chosen, which the resolved config stores in place of the
// budget: a resume, or the resolved config run again, gives the same run.
#pragma once

#include <limits>
#include <string>

#include "gpfd/run/discovery.hpp"
#include "gpfd/run/experiment_config.hpp"

namespace gpfd::run {

// Wall seconds per unit of work, spread over the run's workers (a batch's wall time divided by
// its size, each batch two or four per worker).
struct CostMeasure {
  double randomEvaluation = 0.0;  // A fitness evaluation of a random genome (generation 0).
  // One of a set that learns (later generations): the original variables' as a genome, scaled by
  // (1 + growth) / 2 (at least a random genome's), where growth is the ratio of the steps per
  // episode in the last quarter of the longest training measured (the confirmation's, else the
  // trial's) to those over a whole trial.
  double learnedEvaluation = 0.0;
  double growth = 1.0;
  double validationRun = 0.0;    // A validation training of the original variables.
  double confirmationRun = 0.0;  // A confirmation training of the original variables.
  double noLearningValidation = 0.0, noLearningConfirmation = 0.0;  // Of the no-learning reference.
  // Successive halving (fitness.promote): per individual and generation, the longer rungs' cost,
  // each rung's evaluation of the original variables times the share promoted to it
  // (promote^r); 0 without it.
  double rungEvaluations = 0.0;
  double seconds = 0.0;  // The measurement's own wall time.
  // The validation's and confirmation's trainings estimated from the trial's (scaled by the
  // learner's budget parameter) where measuring them would pass measureCosts' maxSeconds.
  bool estimated = false;
};

// Measures on fresh seeds of their own (never the run's), with the evaluator and trial runner the
// run will use (`options`: its factory, or threads); the evaluations are measured in rounds until
// `minSeconds` have passed.
// `maxSeconds`: where measuring the validation's and confirmation's trainings would end the
// measurement past it, they are estimated from the trial's instead (CostMeasure::estimated).
CostMeasure measureCosts(const ExperimentConfig& config, const DiscoveryOptions& options,
                         double minSeconds,
                         double maxSeconds = std::numeric_limits<double>::infinity());
// The share of a budget spent measuring evaluations at least (kMeasureShare x budget), and at
// most, trainings included, where they are not estimated (kMeasureMaxShare x budget).
inline constexpr double kMeasureShare = 0.02;
inline constexpr double kMeasureMaxShare = 0.1;
// The share of a budget that the learner's choice (learner.choose) may take: its first
// candidate's trainings size the rest (run/learner_choice.hpp).
inline constexpr double kChoiceShare = 0.25;

// What a budget's call spent before sizing: for a refusal that names a budget that works.
struct BudgetSpent {
  double budget = 0.0;       // The whole budget, seconds.
  double choice = 0.0;       // Choosing the learner's settings (0: no choice).
  double choiceFirst = 0.0;  // Its first candidate's trainings, which it always makes.
  // The choice's first training was predicted, not played: alone it passes the choice's share.
  bool choiceFirstPredicted = false;
};
// A budget (a multiple of 10 s) that holds the choice, the measurement and `runsSeconds` of
// runs at their smallest sizes, with a margin: what a refusal names.
double sufficientBudget(const CostMeasure& costs, double runsSeconds, const BudgetSpent& spent);

// The sizes chosen for a budget, and the times they are predicted to take.
struct BudgetSizes {
  int population = 0;
  int generations = 0;  // As predicted; after each generation, fitted to the deadline.
  int candidates = 0, seeds = 0, confirmSeeds = 0;
  double predictedSeconds = 0.0;  // Of one run at the generations expected.
  double finishSeconds = 0.0;     // Of its validation and confirmation.
  // Their trainings as a multiple of a GP trial's (DiscoveryOptions::finishTrainings).
  double finishTrainings = 0.0;
};

// The minimum population, and the population-to-generations ratio aimed at (the paper's 100 x
// 50), kept within [kMinRatio, kMaxRatio] where the minimum sizes force it.
inline constexpr int kMinPopulation = 10;
inline constexpr double kRatio = 2.0;
// Share of a run's time that validation and confirmation may take at most; beyond it their seeds
// (not below 10 and 2 per look) and candidates (not below 3) shrink.
inline constexpr double kValidationShare = 0.3;
// The share of a generation after the first expected to be evaluated, re-evaluations included
// (elitism and the fitness cache spare the rest; 0.14 to 0.6 in runs of cartpole-quick): it only
// sets the population, the deadline ends the generations.
inline constexpr double kFreshShare = 0.65;

// Wall seconds of one trial training of the original variables (on the run's trial runner, else
// one thread): what refuseBeforeMeasuring predicts from.
double timeOneTraining(const ExperimentConfig& config, const DiscoveryOptions& options);
// Wall seconds of one trial training predicted from `seconds`, those of one training under
// `budget` (in proportion to the learner's budget parameter, pg's updates; the same where it has
// none): the learner choice's first training, where it left no time to time one.
double trialSecondsFrom(const ExperimentConfig& config, double seconds,
                        LearningTask::Budget budget);
// InputError at `where`, naming a budget that works (sufficientBudget), where the measurement
// and `runs` smallest runs, predicted from `oneTraining` (each training at its cost, spread over
// `workers`), cannot fit the `seconds` left: on a slow task the refusal comes before the
// measurement, which alone may take longer than the budget. `predictedTraining`: `oneTraining`
// comes from another training than a trial's (the learner choice's), and the text says so.
void refuseBeforeMeasuring(const ExperimentConfig& config, double oneTraining, int workers,
                           double seconds, const BudgetSpent& spent, const std::string& where,
                           int runs, bool predictedTraining = false);

// Sizes for each of `runs` runs of `seconds` (the measurement's time already spent), from
// `config`'s own sizes as the upper bound of the validation's. InputError at `where` when not even
// the smallest run fits, naming a whole budget that would (sufficientBudget), `spent` included.
BudgetSizes sizeToBudget(const ExperimentConfig& config, const CostMeasure& costs, double seconds,
                         const std::string& where, int runs, const BudgetSpent& spent);
// The predicted seconds of validation and confirmation at `sizes`.
double finishSeconds(const ExperimentConfig& config, const CostMeasure& costs,
                     const BudgetSizes& sizes);

// `config` with the sizes, and no budget left.
ExperimentConfig withSizes(ExperimentConfig config, const BudgetSizes& sizes);

// What was measured and chosen, as JSON (run.json's "time_budget") and in one line of text.
std::string budgetJson(double budget, const CostMeasure& costs, const BudgetSizes& sizes);
std::string budgetText(double budget, const CostMeasure& costs, const BudgetSizes& sizes, int runs);

}  // namespace gpfd::run
