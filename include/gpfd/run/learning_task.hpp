// run: fitness from learning trials. A LearningTask makes, from an experiment's config, a fresh
// environment and the learner for each learning run, and scores short trials.
#pragma once

#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpfd/expr/genome.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/run/experiment_config.hpp"
#include "gpfd/run/state_sample.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::run {

class LearningTask {
 public:
  // `budget` selects the learner settings: the short trials of GP fitness, the validation trials
  // (learner.params overridden by validation.params), the confirmation trials (overridden by
  // validation.confirm_params, scored by validation.confirm_measure), or the long training of
  // assessment (overridden by assess.params).
  enum class Budget { Trial, Validation, Confirmation, Assessment };
  LearningTask(const ExperimentConfig& config, Budget budget);

  const ExperimentConfig& config() const { return config_; }
  Budget budget() const { return budget_; }
  // The learner's parameters for this budget: learner.params with the budget's overrides.
  const std::map<std::string, std::string>& learnerParams() const { return learnerParams_; }
  const std::vector<std::string>& stateNames() const { return stateNames_; }
  std::size_t stateDim() const { return stateNames_.size(); }

  // States visited under random actions (config.stateSample of them, seeded from the run's
  // seed), the same on every process that builds the task from the same config.
  const std::shared_ptr<const FeatureSample>& stateSample() const { return sample_; }
  // The features a learner sees for a genome in GP and validation: the genome (without
  // placeholders when config.withOriginal: run/redundancy.hpp), normalised when config.normalise;
  // featureMap follows them with the original variables when config.withOriginal.
  expr::Genome prepared(const expr::Genome& genome) const;
  std::shared_ptr<const features::FeatureMap> featureMap(const expr::Genome& genome) const;

  // One learning run on a fresh environment, seeing states through `map` (inputDim() ==
  // stateDim()). Thread-safe: shares nothing between calls.
  rl::LearningCurve train(const features::FeatureMap& map, Rng& rng) const;
  // Independent learning runs of one map, run k drawing from rngs[k], played together where the
  // learner can (rl::Learner::trainRuns): curve k is exactly train(map, rngs[k]). Thread-safe.
  std::vector<rl::LearningCurve> trainRuns(const features::FeatureMap& map,
                                           std::span<Rng> rngs) const;
  // The trial's performance under the budget's measure (fitness.measure; validation.measure,
  // where given, for validation; validation.confirm_measure for confirmation); -inf when the run
  // diverged or is empty.
  double score(const rl::LearningCurve& curve) const;
  // score() of each curve, in order.
  std::vector<double> scores(const std::vector<rl::LearningCurve>& curves) const;

 private:
  ExperimentConfig config_;
  Budget budget_;
  TrialMeasure measure_;
  std::map<std::string, std::string> learnerParams_;
  std::vector<std::string> stateNames_;
  std::shared_ptr<const FeatureSample> sample_;
  std::shared_ptr<const rl::Learner> learner_;  // From the learner registry.
};

// The features a learner sees for a genome: its compiled features, followed by the original
// state variables when `withOriginal`, placeholders (run/redundancy.hpp) left out; only the
// variables when nothing else remains or the genome is the variables themselves (as a run's
// best.features is when no discovered set beat them).
std::shared_ptr<const features::FeatureMap> genomeFeatureMap(const expr::Genome& genome,
                                                             std::size_t stateDim,
                                                             bool withOriginal);

// The fitness of GP: the mean score of config.trials short trials of task.featureMap(genome),
// trial t seeded from deriveSeed(rng(), t), trained together (task.trainRuns). Any non-finite or
// diverged trial makes the fitness -inf (worst).
double trialFitness(const LearningTask& task, const expr::Genome& genome, Rng& rng);

// Successive halving's longer rungs (fitness.promote), shortest first: the middle rung when
// fitness.rung_params is set, then the confirmation's training. Each is the run's config with its
// short trial made the rung's training (learner.params overridden, the rung's measure) and
// successive halving off, so that trialFitness of LearningTask(rung, Budget::Trial) is the rung's
// evaluation, on any evaluator. Empty when fitness.promote is 0.
std::vector<ExperimentConfig> fitnessRungs(const ExperimentConfig& config);

}  // namespace gpfd::run
