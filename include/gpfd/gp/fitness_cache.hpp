// gp: a fitness cache keyed by the canonical (simplified) genome, in front of any evaluator, so
// that identical individuals are evaluated once. Deterministic: within a batch, the first
// occurrence of a key (in batch order) is evaluated and later ones copy its value.
#pragma once

#include <map>
#include <string>

#include "gpfd/gp/evaluator.hpp"

namespace gpfd::gp {

// The canonical key of a genome: its simplified features as S-expressions joined by " ; ".
std::string canonicalKey(const expr::Genome& genome);

class CachingEvaluator final : public Evaluator {
 public:
  explicit CachingEvaluator(Evaluator& inner) : inner_(inner) {}
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override;

  // Cache hits and genomes actually evaluated during the last evaluate().
  int lastHits() const { return lastHits_; }
  int lastEvaluated() const { return lastEvaluated_; }
  // The cache itself, for checkpoints.
  const std::map<std::string, double>& entries() const { return entries_; }
  void setEntries(std::map<std::string, double> entries) { entries_ = std::move(entries); }

 private:
  Evaluator& inner_;
  std::map<std::string, double> entries_;
  int lastHits_ = 0;
  int lastEvaluated_ = 0;
};

}  // namespace gpfd::gp
