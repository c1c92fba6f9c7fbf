#include "gpfd/experiments/fitness_noise.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <array>
#include <cmath>

#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/statistics.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::experiments {
using namespace gpfd::run;  // The run module's names, used throughout.

NoiseReport measureFitnessNoise(const ExperimentConfig& config,
                                const std::vector<expr::Genome>& genomes, int pairs,
                                int replications, std::uint64_t seed, int threads) {
  if (genomes.size() < 2) throw InputError("needs at least 2 distinct genomes", "fitness-noise");
  const LearningTask task(config, LearningTask::Budget::Trial);
  Rng pick(seed);
  NoiseReport report;
  for (int p = 0; p < pairs; ++p) {
    PairNoise pair;
    pair.a = pick.below(genomes.size());
    do {
      pair.b = pick.below(genomes.size());
    } while (pair.b == pair.a);
    report.pairs.push_back(pair);
  }
  // fitness[p][r][0..2]: a and b on the shared seed, b on an independent seed.
  const auto reps = static_cast<std::size_t>(replications);
  std::vector<std::vector<std::array<double, 3>>> fitness(report.pairs.size(),
                                                          std::vector<std::array<double, 3>>(reps));
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, report.pairs.size() * reps * 3, [&](std::size_t job) {
      const std::size_t p = job / (reps * 3), r = job / 3 % reps, k = job % 3;
      const auto& pair = report.pairs[p];
      Rng rng(deriveSeed(seed, p, r, k == 2 ? 1 : 0));
      fitness[p][r][k] = trialFitness(task, genomes[k == 0 ? pair.a : pair.b], rng);
    });
  });
  std::size_t counted = 0;
  std::vector<double> logRatios;
  for (std::size_t p = 0; p < report.pairs.size(); ++p) {
    std::vector<double> a, b, paired, unpaired;
    for (const auto& f : fitness[p]) {
      a.push_back(f[0]);
      b.push_back(f[1]);
      paired.push_back(f[0] - f[1]);
      unpaired.push_back(f[0] - f[2]);
    }
    auto& pair = report.pairs[p];
    const auto variance = [](const std::vector<double>& v) {
      const double sd = summarize(v).stddev;
      return sd * sd;
    };
    pair.sdA = summarize(a).stddev;
    pair.sdB = summarize(b).stddev;
    pair.pairedVariance = variance(paired);
    pair.unpairedVariance = variance(unpaired);
    if (!std::isfinite(pair.pairedVariance) || !std::isfinite(pair.unpairedVariance)) continue;
    ++counted;  // Pairs with a diverged trial have no variance and are left out of the means.
    report.meanPairedVariance += pair.pairedVariance;
    report.meanUnpairedVariance += pair.unpairedVariance;
    if (pair.pairedVariance < pair.unpairedVariance) ++report.pairsLowerWhenPaired;
    if (pair.pairedVariance > 0 && pair.unpairedVariance > 0) {
      logRatios.push_back(std::log(pair.pairedVariance / pair.unpairedVariance));
    }
  }
  double logSum = 0.0;
  for (const double r : logRatios) logSum += r;
  if (!logRatios.empty()) {
    report.geometricMeanRatio = std::exp(logSum / static_cast<double>(logRatios.size()));
    report.logRatioP = wilcoxonSignedRank(logRatios).p;
  }
  report.meanPairedVariance /= static_cast<double>(counted);
  report.meanUnpairedVariance /= static_cast<double>(counted);
  report.pairsCounted = static_cast<int>(counted);
  return report;
}

}  // namespace gpfd::experiments
