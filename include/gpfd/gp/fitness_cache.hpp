// gp: a fitness cache keyed by the canonical (simplified) genome, in front of any evaluator. It
// keeps, per genome, the mean of every trial score it has seen and the number of trials behind
// it, so that a noisy fitness is not frozen at its first (possibly lucky) draw: a genome met again
// (an elite, a clone, a rediscovery) gets fresh trials, on the new seeds it comes with, until it
// has `maxTrials` of them. Deterministic: within a batch, the first occurrence of a key (in batch
// order) is evaluated and later ones share its result.
#pragma once

#include <map>
#include <string>

#include "gpfd/gp/evaluator.hpp"

namespace gpfd::gp {

// The canonical key of a genome: its simplified features as S-expressions joined by " ; ".
std::string canonicalKey(const expr::Genome& genome);
// The simplified genome a canonical key stands for (variables as x[i]); InputError when `key` is
// not a key.
expr::Genome genomeFromKey(const std::string& key);

// What the cache knows of one genome. A non-finite mean (a diverged trial) is final: the genome
// keeps the worst fitness and is never evaluated again.
struct FitnessRecord {
  double mean = 0.0;  // Mean score over `trials` trials.
  int trials = 0;
};

class CachingEvaluator final : public Evaluator {
 public:
  // One evaluation by `inner` is the mean of `trialsPerEvaluation` trials. `maxTrials` caps the
  // trials a genome accumulates through re-evaluation; 0 turns re-evaluation off (a genome keeps
  // its first fitness). At most `maxReevaluations` genomes are re-evaluated per evaluate() call,
  // those with the best mean first (they decide selection and the hall of fame); -1: no limit.
  // InputError unless maxTrials is 0 or at least trialsPerEvaluation.
  CachingEvaluator(Evaluator& inner, int trialsPerEvaluation, int maxTrials,
                   int maxReevaluations = -1);
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override;

  // During the last evaluate(): genomes sent to `inner` (new and re-evaluated), those of them
  // that were re-evaluations, and genomes answered from the cache alone.
  int lastEvaluated() const { return lastEvaluated_; }
  int lastReevaluated() const { return lastReevaluated_; }
  int lastHits() const { return lastHits_; }
  int trialsPerEvaluation() const { return trialsPerEvaluation_; }
  // The cache itself, for checkpoints and the hall of fame.
  const std::map<std::string, FitnessRecord>& entries() const { return entries_; }
  void setEntries(std::map<std::string, FitnessRecord> entries) { entries_ = std::move(entries); }

 private:
  bool wantsTrials(const FitnessRecord& record) const;

  Evaluator& inner_;
  int trialsPerEvaluation_;
  int maxTrials_;
  int maxReevaluations_;
  std::map<std::string, FitnessRecord> entries_;
  int lastEvaluated_ = 0;
  int lastReevaluated_ = 0;
  int lastHits_ = 0;
};

}  // namespace gpfd::gp
