#include "gpfd/gp/fitness_cache.hpp"

#include "gpfd/expr/print.hpp"
#include "gpfd/expr/simplify.hpp"

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

std::vector<double> CachingEvaluator::evaluate(const std::vector<const expr::Genome*>& genomes,
                                               const std::vector<std::uint64_t>& seeds) {
  std::vector<std::string> keys(genomes.size());
  std::vector<const expr::Genome*> missing;
  std::vector<std::uint64_t> missingSeeds;
  std::map<std::string, std::size_t> pending;  // Key -> index in `missing`.
  for (std::size_t i = 0; i < genomes.size(); ++i) {
    keys[i] = canonicalKey(*genomes[i]);
    if (entries_.count(keys[i]) || pending.count(keys[i])) continue;
    pending[keys[i]] = missing.size();
    missing.push_back(genomes[i]);
    missingSeeds.push_back(seeds[i]);
  }
  const auto fresh = inner_.evaluate(missing, missingSeeds);
  for (const auto& [key, index] : pending) entries_[key] = fresh[index];
  std::vector<double> out(genomes.size());
  for (std::size_t i = 0; i < genomes.size(); ++i) out[i] = entries_.at(keys[i]);
  lastEvaluated_ = static_cast<int>(missing.size());
  lastHits_ = static_cast<int>(genomes.size() - missing.size());
  return out;
}

}  // namespace gpfd::gp
