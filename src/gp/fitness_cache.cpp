#include "gpfd/gp/fitness_cache.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gpfd/expr/parse.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::gp {

std::string canonicalKey(const expr::Genome& genome) {
  const expr::Genome simple = expr::simplify(genome);
  std::string key;
  for (std::size_t k = 0; k < simple.featureCount(); ++k) {
    if (k > 0) key += " ; ";
    key += expr::toSexpr(simple.feature(k), {});
  }
  return key;
}

expr::Genome genomeFromKey(const std::string& key) {
  // Index-only names: any x[i] up to the hard size cap parses.
  static const expr::VariableNames names(65535, "");
  static const std::string separator = " ; ";
  expr::Genome genome;
  for (std::size_t from = 0;;) {
    const std::size_t end = key.find(separator, from);
    genome.addFeature(expr::parseSexpr(key.substr(from, end - from), names));
    if (end == std::string::npos) return genome;
    from = end + separator.size();
  }
}

CachingEvaluator::CachingEvaluator(Evaluator& inner, int trialsPerEvaluation, int maxTrials,
                                   int maxReevaluations)
    : inner_(inner),
      trialsPerEvaluation_(trialsPerEvaluation),
      maxTrials_(maxTrials),
      maxReevaluations_(maxReevaluations) {
  if (trialsPerEvaluation < 1) throw InputError("must be at least 1", "fitness.trials");
  if (maxTrials != 0 && maxTrials < trialsPerEvaluation) {
    throw InputError("must be 0 (no re-evaluation) or at least fitness.trials (" +
                         std::to_string(trialsPerEvaluation) + ")",
                     "fitness.max_trials");
  }
}

bool CachingEvaluator::wantsTrials(const FitnessRecord& record) const {
  return maxTrials_ > 0 && std::isfinite(record.mean) &&
         record.trials + trialsPerEvaluation_ <= maxTrials_;
}

std::vector<double> CachingEvaluator::evaluate(const std::vector<const expr::Genome*>& genomes,
                                               const std::vector<std::uint64_t>& seeds) {
  std::vector<std::string> keys(genomes.size());
  std::vector<const expr::Genome*> batch;
  std::vector<std::uint64_t> batchSeeds;
  std::map<std::string, std::size_t> pending;  // Key -> index in `batch`.
  std::vector<std::size_t> again;              // First occurrences of known keys wanting trials.
  for (std::size_t i = 0; i < genomes.size(); ++i) {
    keys[i] = canonicalKey(*genomes[i]);
    if (pending.count(keys[i])) continue;
    const auto known = entries_.find(keys[i]);
    if (known != entries_.end()) {
      if (wantsTrials(known->second)) {
        pending[keys[i]] = std::numeric_limits<std::size_t>::max();  // Decided below.
        again.push_back(i);
      }
      continue;
    }
    pending[keys[i]] = batch.size();
    batch.push_back(genomes[i]);
    batchSeeds.push_back(seeds[i]);
  }
  // The best known genomes first, in batch order among equals, up to the limit.
  std::stable_sort(again.begin(), again.end(), [&](std::size_t a, std::size_t b) {
    return entries_.at(keys[a]).mean > entries_.at(keys[b]).mean;
  });
  if (maxReevaluations_ >= 0 && again.size() > static_cast<std::size_t>(maxReevaluations_)) {
    for (std::size_t j = static_cast<std::size_t>(maxReevaluations_); j < again.size(); ++j) {
      pending.erase(keys[again[j]]);
    }
    again.resize(static_cast<std::size_t>(maxReevaluations_));
  }
  for (const std::size_t i : again) {
    pending[keys[i]] = batch.size();
    batch.push_back(genomes[i]);
    batchSeeds.push_back(seeds[i]);
  }
  const int reevaluated = static_cast<int>(again.size());
  const auto fresh = inner_.evaluate(batch, batchSeeds);
  constexpr double worst = -std::numeric_limits<double>::infinity();
  for (const auto& [key, index] : pending) {
    const double value = std::isfinite(fresh[index]) ? fresh[index] : worst;
    FitnessRecord& record = entries_[key];
    if (record.trials == 0 || !std::isfinite(value)) {
      record.mean = value;  // A first evaluation keeps its exact value.
    } else {
      const double n = record.trials, k = trialsPerEvaluation_;
      record.mean = (record.mean * n + value * k) / (n + k);
    }
    record.trials += trialsPerEvaluation_;
  }
  std::vector<double> out(genomes.size());
  for (std::size_t i = 0; i < genomes.size(); ++i) out[i] = entries_.at(keys[i]).mean;
  lastEvaluated_ = static_cast<int>(batch.size());
  lastReevaluated_ = reevaluated;
  lastHits_ = static_cast<int>(genomes.size() - batch.size());
  return out;
}

}  // namespace gpfd::gp
