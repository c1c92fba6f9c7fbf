// run: the validation stage that decides what a discovery run returns. The GP's own fitness of
// its best genome is the maximum of many noisy estimates, so it overstates that genome (the
// winner's curse). Here the best distinct genomes (a hall of fame) and the original state
// variables are each trained again on the same fresh validation seeds, and the best mean wins.
// The winner is then confirmed: it and the original variables are trained once more on other
// fresh seeds (possibly with a longer trial); a discovered winner that does not beat the original
// variables there is not returned, and the confirmation's scores are the ones reported.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "gpfd/expr/features_file.hpp"
#include "gpfd/gp/fitness_cache.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/run/trial_runner.hpp"

namespace gpfd::run {

// A feature set scored on the validation seeds.
struct ValidatedSet {
  std::string key;      // The genome's canonical key; empty for the original variables.
  expr::Genome genome;  // Simplified, as the key says (empty for the original variables).
  int generation = -1;  // The generation after which it was validated.
  double gpFitness = std::numeric_limits<double>::quiet_NaN();  // Penalised GP fitness then.
  int gpTrials = 0;                                             // Trials behind gpFitness.
  std::vector<double> scores;  // One trial score per validation seed, in seed order.

  bool isOriginal() const { return key.empty(); }
  // Nodes: the genome's, or one per state variable for the original variables.
  std::size_t size(std::size_t stateDim) const;
  Summary summary() const { return summarize(scores); }
};

// The validation winner and the original variables trained once more, on fresh seeds and with
// the confirmation trial (config.validation.confirm_*): scores that the choice among the
// candidates did not see, hence unbiased estimates of what is returned.
struct Confirmation {
  std::string key;               // The validation winner's key; empty: the original variables won.
  std::vector<double> winner;    // The winner's scores, in seed order (empty when key is empty).
  std::vector<double> original;  // The original variables' scores on the same seeds.
  // The no-learning reference on the same seeds (empty in runs made before it existed), and the
  // level at which a discovered winner must beat it: the O'Brien-Fleming level of the last look
  // (confirmationEndsAtLook, run/sequential_test.hpp).
  std::vector<double> noLearning;
  double noLearningLevel = 0.05;

  bool done() const { return !original.empty(); }
  // Whether a discovered winner holds: its mean difference from the original variables is > 0.
  bool held() const;
  // Whether a discovered winner is significantly better than no learning (paired t-test p below
  // noLearningLevel, difference > 0); true when no-learning was not scored.
  bool beatsNoLearning() const;
};

// The validation stage's results so far.
struct ValidationState {
  std::vector<ValidatedSet> sets;  // Every set validated, the original variables included.
  // The no-learning reference (TrialFeatures::noLearning: the learner sees one feature that is
  // always 0) on the validation seeds: a reference, never a candidate. Empty until first scored,
  // and in runs made before it existed.
  std::vector<double> noLearning;
  Confirmation confirmation;  // Of the final choice; not done when confirm_seeds is 0.
  // config.validation.parsimonySe, which chooseWinner(state) applies; set from the run's config
  // (not saved in checkpoints).
  double parsimonySe = 0.0;
  int finalGeneration = -1;  // The last generation after which the winner was chosen.
  double seconds = 0.0;      // Wall time spent validating and confirming.
};

// A member of the hall of fame: one of the best distinct genomes the cache has scored.
struct HallOfFameEntry {
  std::string key;
  expr::Genome genome;   // Simplified.
  double fitness = 0.0;  // Mean trial score minus the size penalty.
  int trials = 0;
};

// The `size` distinct genomes of the cache with the best penalised mean fitness (finite only,
// placeholders alone left out: run/redundancy.hpp), best first; ties keep key order.
std::vector<HallOfFameEntry> hallOfFame(const std::map<std::string, gp::FitnessRecord>& cache,
                                        int size, double sizePenalty);

// Trains feature sets on validation seeds: seed m is deriveSeed(config.seed, stream, m) for
// every set, so sets are compared on paired trials. A trial is one learning run with the
// validation budget (config.validation.seeds of them per set), scored as GP scores a trial; the
// runner trains them (on threads, or on worker processes), which changes no score.
class Validator {
 public:
  static constexpr std::uint64_t kValidationStream = 2;
  // Fresh seeds for re-measuring a returned set, never used by the run itself.
  static constexpr std::uint64_t kRemeasureStream = 3;
  static constexpr std::uint64_t kConfirmationStream = 4;

  // Validation trials on config.validation.seeds seeds of `stream`. `runner` must outlive it.
  Validator(const ExperimentConfig& config, TrialRunner& runner,
            std::uint64_t stream = kValidationStream);
  // `seeds` trials of the `budget` (Validation or Confirmation) on seeds of `stream`.
  Validator(const ExperimentConfig& config, TrialRunner& runner, LearningTask::Budget budget,
            int seeds, std::uint64_t stream);
  // The trials that confirm the choice: config.validation.confirm_seeds seeds of
  // kConfirmationStream with the confirmation trial.
  static Validator confirmation(const ExperimentConfig& config, TrialRunner& runner);
  // scores[set][m] of the feature sets.
  std::vector<std::vector<double>> score(const std::vector<TrialFeatures>& sets) const;
  // scores[set][m - from] on seeds m in [from, to) (a seed's score does not depend on the range).
  std::vector<std::vector<double>> score(const std::vector<TrialFeatures>& sets, int from,
                                         int to) const;
  // scores[set][m] of genomes as GP sees them (task().featureMap); null: the original variables.
  std::vector<std::vector<double>> score(const std::vector<const expr::Genome*>& sets) const;
  // The feature sets of `genomes` as score(genomes) trains them.
  std::vector<TrialFeatures> features(const std::vector<const expr::Genome*>& genomes) const;
  const LearningTask& task() const { return task_; }
  int seeds() const { return seeds_; }

 private:
  LearningTask task_;
  TrialRunner* runner_;
  int seeds_;
  std::uint64_t stream_;
};

// The validation winner, an index into `sets` (which must include the original variables): the
// set with the best mean score; ties go to the smaller set, then to the original variables.
// With parsimonySe > 0 a discovered winner gives way to the simplest validated set made of some,
// not all, of its features (fewest features, then fewest nodes, then the better mean) whose mean
// is at least the winner's minus parsimonySe standard errors of the winner's mean: the
// one-standard-error rule (Breiman, Friedman, Olshen & Stone 1984, Classification and
// Regression Trees, section 3.4.3), kept to nested sets, so that a feature stays only where the
// seeds show that it adds something.
std::size_t chooseWinner(const std::vector<ValidatedSet>& sets, std::size_t stateDim,
                         double parsimonySe = 0.0);
// chooseWinner(state.sets, stateDim, state.parsimonySe).
std::size_t chooseWinner(const ValidationState& state, std::size_t stateDim);

// The index of the original variables in `sets`.
std::size_t originalIndex(const std::vector<ValidatedSet>& sets);

// What the run returns: the validation winner, or the original variables when a discovered
// winner did not hold on confirmation or is not significantly better than no learning (on the
// confirmation seeds at Confirmation::noLearningLevel, else on the validation seeds at 0.05): a
// set that only stops learning is never returned as a discovery. An index into state.sets.
std::size_t returnedIndex(const ValidationState& state, std::size_t stateDim);

// The scores that stand for the returned set, the original variables and the no-learning
// reference: the confirmation's when it was done (unbiased), else the validation's (biased
// upwards by the choice). `noLearning` is empty where it was not scored.
struct ReportedScores {
  const std::vector<double>* returned;
  const std::vector<double>* original;
  bool confirmed;
  const std::vector<double>* noLearning;
};
ReportedScores reportedScores(const ValidationState& state, std::size_t stateDim);

// Where a run stands against the no-learning reference.
struct NoLearningVerdict {
  bool scored = false;        // False in runs made before the reference existed.
  Summary noLearning;         // On the reported seeds.
  PairedComparison original;  // Original variables - no learning, on the reported seeds.
  bool learnerHarms = false;  // The original variables significantly worse (p < 0.05).
  // A discovered validation winner not returned because it is not significantly better than no
  // learning (though it held against the original variables, or was not confirmed), and its
  // comparison (winner - no learning) on the seeds that decided it.
  bool winnerNoBetter = false;
  PairedComparison winner;
};
NoLearningVerdict noLearningVerdict(const ValidationState& state, std::size_t stateDim);

// validation.csv: every set, best mean first, with its comparison to the original variables;
// `selected` marks the set at index `returned`; then, unranked, the row `no-learning` when
// `noLearning` holds its scores.
std::string formatValidationCsv(const std::vector<ValidatedSet>& sets, std::size_t returned,
                                const std::vector<std::string>& stateNames,
                                const std::vector<double>& noLearning = {});
// confirmation.csv: the confirmed sets (the winner, the original variables), which is returned,
// and the row `no-learning` where it was scored.
std::string formatConfirmationCsv(const ValidationState& state,
                                  const std::vector<std::string>& stateNames);
// The complexity front: indices of the best validated set at each size, smallest first; a set
// is on it only where its mean beats every smaller set's.
std::vector<std::size_t> frontIndices(const std::vector<ValidatedSet>& sets, std::size_t stateDim);
// front.csv: the front's sets with their selection scores (validation means) and expressions.
std::string formatFrontCsv(const std::vector<ValidatedSet>& sets,
                           const std::vector<std::string>& stateNames);
// The front as a text table for the terminal (scores: selection, as in front.csv).
std::string formatFrontTable(const std::vector<ValidatedSet>& sets,
                             const std::vector<std::string>& stateNames);

// The features file of what the run returns (`prepared`: its genome as the learner sees it,
// LearningTask::prepared). Its scores, in one vocabulary: `# confirmed` (the score on the fresh
// confirmation seeds, unbiased; only when the choice was confirmed) with `# confirmed_by`,
// `# selection` (the mean over the validation seeds that chose among the candidates, biased
// upwards for the winner) with `# selection_by`, `# original` (the original variables on the
// seeds of the reported score: confirmation's, else validation's), `# no_learning` (the
// no-learning reference on those seeds), `# gp_fitness` (the GP's own estimate, biased; a
// discovered set only), `# verdict`, and `# warning` when the learner harms (the original
// variables significantly worse than no learning).
expr::FeaturesFile returnedFeaturesFile(const ValidationState& state, const expr::Genome& prepared,
                                        const LearningTask& task);

// A comparison in words as its significance allows: "better|worse than OTHER on SEEDS by D
// (paired t-test p = P)" where p < 0.05, else "not significantly different from OTHER on SEEDS
// (difference D, paired t-test p = P)".
std::string comparisonVerdict(const PairedComparison& paired, const std::string& other,
                              const std::string& seeds);

// "MEAN +- SE (M trials)".
std::string formatMeanSe(const Summary& summary);

}  // namespace gpfd::run
