// `gpfd fitness-noise`: the noise of GP fitness in a run's final population, and whether common
// random numbers (fitness.common_seeds) lower the variance of fitness differences.
#include <fmt/format.h>

#include <set>

#include "command.hpp"
#include "gpfd/experiments/fitness_noise.hpp"
#include "gpfd/gp/fitness_cache.hpp"
#include "gpfd/run/checkpoint.hpp"
#include "gpfd/run/stored_config.hpp"
#include "gpfd/service/resources.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::app {
namespace {

struct NoiseOptions {
  std::string run;
  int pairs = 10;
  int replications = 20;
  std::uint64_t seed = 1;
  int threads = 0;
};

int fitnessNoise(const NoiseOptions& o) {
  const std::string path = o.run + "/checkpoint.json";
  const auto checkpoint = run::parseCheckpoint(readFile(path), path);
  const auto config = run::parseStoredExperimentConfig(checkpoint.config, path + " (config)");
  // The distinct genomes of the final population that did not diverge.
  std::vector<expr::Genome> genomes;
  std::set<std::string> keys;
  for (const auto& ind : checkpoint.state.population) {
    if (std::isfinite(ind.fitness) && keys.insert(gp::canonicalKey(ind.genome)).second) {
      genomes.push_back(ind.genome);
    }
  }
  fmt::print(
      "gpfd fitness-noise: {} ({}), {} distinct genomes, {} pairs x {} replications of "
      "{} trials\n",
      config.name, o.run, genomes.size(), o.pairs, o.replications, config.trials);
  std::fflush(stdout);
  const auto report = experiments::measureFitnessNoise(config, genomes, o.pairs, o.replications,
                                                       o.seed, service::usableThreads(o.threads));
  fmt::print("pair  sd(a)     sd(b)     var(a-b) paired  var(a-b) unpaired\n");
  for (std::size_t p = 0; p < report.pairs.size(); ++p) {
    const auto& pair = report.pairs[p];
    fmt::print("{:4}  {:<8.4g}  {:<8.4g}  {:<15.4g}  {:.4g}\n", p + 1, pair.sdA, pair.sdB,
               pair.pairedVariance, pair.unpairedVariance);
  }
  fmt::print(
      "mean variance of fitness differences over {} pairs: paired (common seeds) {:.4g}, "
      "unpaired {:.4g}, ratio {:.3f}; lower when paired in {} of {} pairs; per-pair ratio "
      "{:.3f} (geometric mean), Wilcoxon signed-rank p = {:.3g} on its logarithm\n",
      report.pairsCounted, report.meanPairedVariance, report.meanUnpairedVariance,
      report.meanPairedVariance / report.meanUnpairedVariance, report.pairsLowerWhenPaired,
      report.pairsCounted, report.geometricMeanRatio, report.logRatioP);
  return 0;
}

const CommandRegistration registration{
    "fitness-noise", [](CLI::App& app) {
      auto* cmd = app.add_subcommand(
          "fitness-noise",
          "Measure the noise of GP fitness in a run's final population, paired (common seeds) "
          "against unpaired");
      auto o = std::make_shared<NoiseOptions>();
      cmd->add_option("run", o->run, "A discovery run's results directory")->required();
      cmd->add_option("--pairs", o->pairs, "Random pairs of genomes (1-1000)")
          ->check(bounded(1, 1000))
          ->capture_default_str();
      cmd->add_option("--replications", o->replications,
                      "Fitness evaluations of each genome per scheme (2-10000)")
          ->check(bounded(2, 10000))
          ->capture_default_str();
      cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str()->check(seedValue());
      cmd->add_option("--threads", o->threads, "Worker threads (0: all cores)")
          ->check(threadCount());
      return [o] { return fitnessNoise(*o); };
    }};

}  // namespace
}  // namespace gpfd::app
