#include "gpfd/gp/evolution.hpp"

#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <set>

#include "gpfd/expr/eval.hpp"
#include "gpfd/gp/fitness_cache.hpp"
#include "gpfd/util/error.hpp"
#include "small_space.hpp"

namespace gpfd::gp {
namespace {

using fixtures::smallSpace;

// A cheap fitness that uses its RNG: closeness of the first feature to a*b on noisy samples.
double noisyFitness(const expr::Genome& g, Rng& rng) {
  double error = 0.0;
  std::vector<double> out(g.featureCount());
  for (int i = 0; i < 20; ++i) {
    const double state[] = {rng.uniform(-1, 1), rng.uniform(-1, 1)};
    expr::evaluate(g, state, out.data());
    const double d = out[0] - state[0] * state[1];
    error += d * d;
  }
  return -error;
}

// A run on noisyFitness behind a cache; maxTrials 0: a genome keeps its first fitness.
std::vector<GenerationStats> runOnce(std::uint64_t seed, int maxTrials = 0,
                                     bool commonRandomNumbers = false, bool distinct = false) {
  GpConfig config;
  config.population = 40;
  config.generations = 8;
  config.sizePenalty = 1e-3;
  config.seed = seed;
  config.commonRandomNumbers = commonRandomNumbers;
  config.distinctOffspring = distinct;
  SerialEvaluator evaluator(noisyFitness);
  CachingEvaluator cache(evaluator, 1, maxTrials);
  Evolution evolution(config, smallSpace(), cache);
  std::vector<GenerationStats> all;
  evolution.run([&](const GenerationStats& s) {
    all.push_back(s);
    return true;
  });
  return all;
}

void expectSameStats(const std::vector<GenerationStats>& a, const std::vector<GenerationStats>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].best, b[i].best);
    EXPECT_EQ(a[i].mean, b[i].mean);
    EXPECT_EQ(a[i].median, b[i].median);
    EXPECT_EQ(a[i].meanSize, b[i].meanSize);
    EXPECT_EQ(a[i].meanFeatures, b[i].meanFeatures);
    EXPECT_EQ(a[i].bestIndividual.genome, b[i].bestIndividual.genome);
  }
}

TEST(Evolution, SameSeedSameStatistics) {
  const auto a = runOnce(11), b = runOnce(11), c = runOnce(12);
  expectSameStats(a, b);
  EXPECT_NE(a.back().mean, c.back().mean);
}

TEST(Evolution, WithoutReevaluationElitesKeepTheirFitnessAndBestNeverDrops) {
  const auto stats = runOnce(3);
  ASSERT_EQ(stats.size(), 8u);
  for (std::size_t i = 1; i < stats.size(); ++i) {
    EXPECT_GE(stats[i].best, stats[i - 1].best);
    EXPECT_EQ(stats[i].evaluations, 40);  // Elites too go to the evaluator (the cache).
  }
}

TEST(Evolution, ReevaluationLetsALuckyBestFall) {
  // With re-evaluation an elite's fitness becomes the mean of more draws, so the best of a noisy
  // problem may fall; without it, it never does (above).
  const auto stats = runOnce(3, 4);
  bool fell = false;
  for (std::size_t i = 1; i < stats.size(); ++i) fell = fell || stats[i].best < stats[i - 1].best;
  EXPECT_TRUE(fell);
  expectSameStats(stats, runOnce(3, 4));
}

// Records the seed each genome was evaluated with.
class SeedRecorder final : public Evaluator {
 public:
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override {
    batches.push_back(seeds);
    return std::vector<double>(genomes.size(), 1.0);
  }
  std::vector<std::vector<std::uint64_t>> batches;
};

TEST(Evolution, CommonRandomNumbersGiveAGenerationOneSeed) {
  for (const bool common : {false, true}) {
    GpConfig config;
    config.population = 10;
    config.generations = 3;
    config.commonRandomNumbers = common;
    SeedRecorder recorder;
    Evolution evolution(config, smallSpace(), recorder);
    evolution.run([](const GenerationStats&) { return true; });
    ASSERT_EQ(recorder.batches.size(), 3u);
    for (const auto& seeds : recorder.batches) {
      ASSERT_EQ(seeds.size(), 10u);
      const auto distinct = std::set<std::uint64_t>(seeds.begin(), seeds.end()).size();
      EXPECT_EQ(distinct, common ? 1u : 10u);
    }
    EXPECT_NE(recorder.batches[0], recorder.batches[1]);
  }
}

TEST(Evolution, TheReducerRewritesEveryNewGenome) {
  GpConfig config;
  config.population = 20;
  config.generations = 4;
  SerialEvaluator evaluator(noisyFitness);
  // Keeps only the first feature of every genome.
  const GenomeReducer firstOnly = [](const expr::Genome& g) {
    expr::Genome out;
    out.addFeature(g.feature(0));
    return out;
  };
  Evolution evolution(config, smallSpace(), evaluator, firstOnly);
  evolution.run([&](const GenerationStats&) {
    for (const auto& ind : evolution.population()) EXPECT_EQ(ind.genome.featureCount(), 1u);
    return true;
  });
}

// How many distinct canonical keys a population holds.
std::size_t distinctKeys(const std::vector<Individual>& population) {
  std::set<std::string> keys;
  for (const auto& ind : population) keys.insert(canonicalKey(ind.genome));
  return keys.size();
}

// Whether a genome reads the variable x0 anywhere.
bool readsX0(const expr::Genome& g) {
  for (std::size_t k = 0; k < g.featureCount(); ++k) {
    for (const auto& node : g.feature(k)) {
      if (node.op == expr::Op::Var && node.var == 0) return true;
    }
  }
  return false;
}

TEST(Evolution, DistinctOffspringKeepEveryGenerationFreeOfRepeats) {
  // A long run on a cached, noise-free fitness converges: without distinct offspring the last
  // generations repeat their best; with it no generation holds a genome twice.
  for (const bool distinct : {false, true}) {
    GpConfig config;
    config.population = 40;
    config.generations = 30;
    config.tournamentSize = 7;
    config.distinctOffspring = distinct;
    SerialEvaluator evaluator([](const expr::Genome& g, Rng&) {
      Rng fixed(1);
      return noisyFitness(g, fixed);
    });
    CachingEvaluator cache(evaluator, 1, 0);
    Evolution evolution(config, smallSpace(), cache);
    std::size_t fewest = 40;
    evolution.run([&](const GenerationStats&) {
      fewest = std::min(fewest, distinctKeys(evolution.population()));
      return true;
    });
    if (distinct) {
      EXPECT_EQ(fewest, 40u);
    } else {
      EXPECT_LT(fewest, 30u);
    }
  }
}

TEST(Evolution, DistinctOffspringAreReproducible) {
  const auto distinct = runOnce(5, 0, false, true);
  expectSameStats(distinct, runOnce(5, 0, false, true));
  EXPECT_NE(distinct.back().mean, runOnce(5).back().mean);  // The option changes the run.
}

TEST(Evolution, TheFilterKeepsRefusedGenomesOut) {
  GpConfig config;
  config.population = 30;
  config.generations = 5;
  config.distinctOffspring = true;
  SerialEvaluator evaluator(noisyFitness);
  Evolution evolution(config, smallSpace(), evaluator, {}, readsX0);
  evolution.run([&](const GenerationStats&) {
    for (const auto& ind : evolution.population()) EXPECT_TRUE(readsX0(ind.genome));
    return true;
  });
}

TEST(Evolution, ASearchSpaceTooSmallForDistinctGenomesStillFillsItsGeneration) {
  // One variable, one feature of depth 1 (one node), no constants: one genome exists.
  SearchSpace tiny = smallSpace();
  tiny.variableCount = 1;
  tiny.limits = {1, 1, 1, 1};
  tiny.initMinDepth = tiny.initMaxDepth = tiny.mutationDepth = 1;
  tiny.primitives.constants.clear();
  tiny.primitives.ephemeral = false;
  GpConfig config;
  config.population = 12;
  config.generations = 3;
  config.distinctOffspring = true;
  SerialEvaluator evaluator(noisyFitness);
  Evolution evolution(config, tiny, evaluator);
  evolution.run([&](const GenerationStats&) {
    EXPECT_EQ(evolution.population().size(), 12u);
    return true;
  });
}

TEST(Evolution, NonFiniteFitnessScoresWorst) {
  GpConfig config;
  config.population = 20;
  config.generations = 2;
  SerialEvaluator evaluator([](const expr::Genome& g, Rng&) {
    return g.featureCount() == 1 ? std::numeric_limits<double>::quiet_NaN() : 1.0;
  });
  Evolution evolution(config, smallSpace(), evaluator);
  const auto stats = evolution.initialize();
  EXPECT_GT(stats.invalid, 0);
  EXPECT_EQ(stats.best, 1.0);
  for (const auto& ind : evolution.population()) {
    if (ind.genome.featureCount() == 1) {
      EXPECT_EQ(ind.fitness, -INFINITY);
    }
  }
}

// Observed operator frequencies match the configured probabilities (chi-square over the operators
// with a positive probability; those with none are never applied).
TEST(Evolution, OperatorFrequenciesMatchProbabilities) {
  GpConfig config;
  config.population = 200;
  config.generations = 30;
  SerialEvaluator evaluator([](const expr::Genome& g, Rng&) { return -double(g.size()); });
  Evolution evolution(config, smallSpace(), evaluator);
  evolution.run([](const GenerationStats&) { return true; });
  const auto probabilities = operatorProbabilities(config);
  EXPECT_NEAR(probabilities[0], 0.7 * 5.0 / 6.0, 1e-12);
  EXPECT_NEAR(probabilities[2], 0.15, 1e-12);
  EXPECT_NEAR(probabilities[3], 0.075, 1e-12);
  const auto& counts = evolution.operatorCounts();
  ASSERT_EQ(counts.size(), probabilities.size());
  double total = 0.0;
  for (long c : counts) total += static_cast<double>(c);
  double chi2 = 0.0;
  int categories = 0;
  for (std::size_t o = 0; o < counts.size(); ++o) {
    if (probabilities[o] == 0) {
      EXPECT_EQ(counts[o], 0) << "operator " << o;
      continue;
    }
    const double expected = total * probabilities[o];
    const double observed = static_cast<double>(counts[o]);
    chi2 += (observed - expected) * (observed - expected) / expected;
    ++categories;
  }
  EXPECT_EQ(categories, 5);  // The paper's five.
  const boost::math::chi_squared distribution(categories - 1);
  const double p = boost::math::cdf(boost::math::complement(distribution, chi2));
  EXPECT_GT(p, 1e-4) << "chi2 = " << chi2 << " over " << total << " draws";
  EXPECT_GT(total, 3000);
}

TEST(Evolution, ConfigValidation) {
  SerialEvaluator evaluator(noisyFitness);
  GpConfig bad;
  bad.elitism = 1.5;
  EXPECT_THROW(Evolution(bad, smallSpace(), evaluator), InputError);
  bad = GpConfig{};
  bad.population = 1;
  EXPECT_THROW(Evolution(bad, smallSpace(), evaluator), InputError);
}

}  // namespace
}  // namespace gpfd::gp
