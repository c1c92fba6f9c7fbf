// run: the checkpoint of a discovery run, written atomically after every generation, from which
// `gpfd evolve --resume` continues with exactly the result an uninterrupted run would give.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "gpfd/gp/evolution.hpp"
#include "gpfd/gp/fitness_cache.hpp"
#include "gpfd/run/validation.hpp"

namespace gpfd::run {

// One row of generations.csv, plus the generation's best genome.
struct GenerationRecord {
  int generation = 0;
  double best = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double meanSize = 0.0;
  double meanFeatures = 0.0;
  int evaluations = 0;    // Genomes actually evaluated (cache hits excluded).
  int reevaluations = 0;  // Of those, genomes met before that got fresh trials.
  int cacheHits = 0;
  double seconds = 0.0;
  expr::Genome bestGenome;
  int promotions = 0;  // Evaluations at successive halving's longer rungs (fitness.promote).
};

struct Checkpoint {
  std::string version;  // gpfd's version; a checkpoint of another version is refused.
  std::string config;   // The resolved config (TOML text) the run was started with.
  gp::EvolutionState state;
  std::map<std::string, gp::FitnessRecord> cache;  // The fitness cache.
  std::vector<GenerationRecord> history;
  ValidationState validation;
};

std::string formatCheckpoint(const Checkpoint& checkpoint);
// InputError naming `source` when the text is not a valid checkpoint.
Checkpoint parseCheckpoint(const std::string& text, const std::string& source);

// generations.csv:
// generation,best,mean,median,mean_size,mean_features,evaluations,reevaluations,cache_hits,seconds
std::string formatGenerationsCsv(const std::vector<GenerationRecord>& history);

}  // namespace gpfd::run
