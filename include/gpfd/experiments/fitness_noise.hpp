// experiments: how noisy GP fitness is, and whether common random numbers help (`gpfd
// fitness-noise`). Selection compares individuals by fitness, a mean of K noisy trials; what
// matters is the variance of the difference of two individuals' fitness. With common random numbers
// both are evaluated on the same trial seeds (paired); otherwise on independent seeds. Pairing
// helps only where trials with the same seed are positively correlated across feature sets.
#pragma once

#include <cstdint>
#include <vector>

#include "gpfd/expr/genome.hpp"
#include "gpfd/run/experiment_config.hpp"

namespace gpfd::experiments {

struct PairNoise {
  std::size_t a = 0, b = 0;       // Indices of the genomes.
  double sdA = 0.0, sdB = 0.0;    // Standard deviation of each one's fitness over replications.
  double pairedVariance = 0.0;    // Of fitness(a) - fitness(b) on the same seeds.
  double unpairedVariance = 0.0;  // Of fitness(a) - fitness(b) on independent seeds.
};

struct NoiseReport {
  std::vector<PairNoise> pairs;
  double meanPairedVariance = 0.0, meanUnpairedVariance = 0.0;
  int pairsCounted = 0;          // Pairs without a diverged trial, over which means are taken.
  int pairsLowerWhenPaired = 0;  // Pairs whose paired variance is below the unpaired one.
  // Over the pairs: log(paired / unpaired variance), its geometric mean as a ratio, and Wilcoxon's
  // signed-rank test of whether it is centred on 0 (pairing neither helps nor hurts).
  double geometricMeanRatio = 1.0;
  double logRatioP = 1.0;
};

// For `pairs` random pairs of distinct genomes (seeded by `seed`), `replications` fitness
// evaluations of each (the config's short trial, config.trials trials each): per replication r,
// a and b on one seed, and b again on an independent seed. Same inputs, same report, whatever
// `threads`.
NoiseReport measureFitnessNoise(const run::ExperimentConfig& config,
                                const std::vector<expr::Genome>& genomes, int pairs,
                                int replications, std::uint64_t seed, int threads);

}  // namespace gpfd::experiments
