// Successive halving in the evolution loop (GpConfig::promote): who is promoted, with which
// seeds, and how selection ranks the rungs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "gpfd/gp/evolution.hpp"
#include "gpfd/util/error.hpp"
#include "small_space.hpp"

namespace gpfd::gp {
namespace {

using fixtures::smallSpace;

// Scores a genome by its size plus `offset` (a pure function of the genome), and records what it
// was asked.
class SizeScorer final : public Evaluator {
 public:
  explicit SizeScorer(double offset) : offset_(offset) {}
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override {
    std::vector<double> out;
    for (const auto* g : genomes) out.push_back(offset_ + static_cast<double>(g->size()));
    asked.push_back(genomes.size());
    seen.push_back(seeds);
    return out;
  }
  std::vector<std::size_t> asked;
  std::vector<std::vector<std::uint64_t>> seen;

 private:
  double offset_;
};

GpConfig halving(int population, double promote) {
  GpConfig config;
  config.population = population;
  config.generations = 3;
  config.promote = promote;
  config.seed = 5;
  return config;
}

TEST(SuccessiveHalving, TheBestShareOfEachRungIsEvaluatedAtTheNext) {
  SizeScorer shortTrials(0.0), middle(1000.0), longest(2000.0);
  Evolution evolution(halving(27, 1.0 / 3), smallSpace(), shortTrials, {}, {}, {&middle, &longest});
  const auto stats = evolution.initialize();
  ASSERT_EQ(middle.asked, std::vector<std::size_t>{9});
  ASSERT_EQ(longest.asked, std::vector<std::size_t>{3});
  EXPECT_EQ(stats.promotions, 12);
  std::vector<int> perRung(3, 0);
  double lowestPromoted = INFINITY, highestLeft = -INFINITY;
  for (const auto& ind : evolution.population()) {
    ++perRung[static_cast<std::size_t>(ind.rung)];
    const double size = static_cast<double>(ind.genome.size());
    if (ind.rung > 0) lowestPromoted = std::min(lowestPromoted, size);
    if (ind.rung == 0) highestLeft = std::max(highestLeft, size);
    // The fitness is the longest rung's.
    EXPECT_EQ(ind.rawFitness, 1000.0 * ind.rung + size);
  }
  EXPECT_EQ(perRung, (std::vector<int>{18, 6, 3}));
  EXPECT_GE(lowestPromoted, highestLeft);  // The best by the short trials went on.
  EXPECT_EQ(evolution.best().rung, 2);
}

TEST(SuccessiveHalving, RungSeedsComeFromTheirOwnStreamAndRepeat) {
  const auto seeds = [] {
    SizeScorer shortTrials(0.0), longest(0.0);
    Evolution evolution(halving(12, 0.25), smallSpace(), shortTrials, {}, {}, {&longest});
    evolution.run([](const GenerationStats&) { return true; });
    return std::make_pair(shortTrials.seen, longest.seen);
  };
  const auto [shortSeeds, rungSeeds] = seeds();
  ASSERT_EQ(rungSeeds.size(), 3u);
  std::set<std::uint64_t> all;
  for (const auto& batch : shortSeeds) all.insert(batch.begin(), batch.end());
  for (const auto& batch : rungSeeds) {
    EXPECT_EQ(batch.size(), 3u);
    for (const auto seed : batch) EXPECT_FALSE(all.contains(seed));
  }
  EXPECT_EQ(seeds(), std::make_pair(shortSeeds, rungSeeds));
}

TEST(SuccessiveHalving, ALongerRungRanksAboveAShorterOneAndANonFiniteFitnessBelowAll) {
  const Individual shortBest{{}, 50.0, 50.0, 0};
  const Individual longWorse{{}, -10.0, -10.0, 1};
  const Individual failed{{}, -INFINITY, -INFINITY, 2};
  EXPECT_TRUE(ranksAbove(longWorse, shortBest));
  EXPECT_FALSE(ranksAbove(shortBest, longWorse));
  EXPECT_TRUE(ranksAbove(shortBest, failed));
  EXPECT_FALSE(ranksAbove(failed, shortBest));
  EXPECT_TRUE(ranksAbove(Individual{{}, 2.0, 2.0, 0}, Individual{{}, 1.0, 1.0, 0}));
}

TEST(SuccessiveHalving, ANonFiniteResultEndsTheClimb) {
  SerialEvaluator shortTrials([](const expr::Genome& g, Rng&) { return double(g.size()); });
  SerialEvaluator fails([](const expr::Genome&, Rng&) { return NAN; });
  SizeScorer longest(0.0);
  Evolution evolution(halving(10, 0.5), smallSpace(), shortTrials, {}, {}, {&fails, &longest});
  const auto stats = evolution.initialize();
  EXPECT_TRUE(longest.asked.empty());
  EXPECT_EQ(stats.promotions, 5);
  // The failed ones rank below every finite one: the best is still an unpromoted individual.
  EXPECT_EQ(evolution.best().rung, 0);
  EXPECT_TRUE(std::isfinite(evolution.best().fitness));
}

TEST(SuccessiveHalving, OffWithoutPromoteAndTheShareIsChecked) {
  SizeScorer shortTrials(0.0), longest(0.0);
  Evolution evolution(halving(10, 0.0), smallSpace(), shortTrials, {}, {}, {&longest});
  EXPECT_EQ(evolution.initialize().promotions, 0);
  EXPECT_TRUE(longest.asked.empty());
  EXPECT_THROW(Evolution(halving(10, 1.0), smallSpace(), shortTrials), InputError);
  EXPECT_THROW(Evolution(halving(10, -0.1), smallSpace(), shortTrials), InputError);
}

}  // namespace
}  // namespace gpfd::gp
