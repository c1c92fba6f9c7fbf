#include "gpfd/experiments/fitness_noise.hpp"

#include <gtest/gtest.h>

#include "../run/cli_helpers.hpp"
#include "gpfd/expr/parse.hpp"

namespace gpfd::experiments {
namespace {
using namespace gpfd::run;

TEST(FitnessNoise, PairingRemovesTheNoiseOfEqualSetsAndIsThreadIndependent) {
  const auto config = loadExperimentConfig(testing::tinyEvolveConfig("noise", 1));
  const expr::VariableNames names{"x", "dx", "th", "dth"};
  std::vector<expr::Genome> genomes(2);
  for (auto& g : genomes) g.addFeature(expr::parseInfix("th + dth", names));  // The same set.
  const auto one = measureFitnessNoise(config, genomes, 3, 6, 5, 1);
  ASSERT_EQ(one.pairs.size(), 3u);
  for (const auto& pair : one.pairs) {
    EXPECT_EQ(pair.pairedVariance, 0.0);  // Same features, same seeds: the same fitness.
    EXPECT_GT(pair.unpairedVariance, 0.0);
    EXPECT_GT(pair.sdA, 0.0);
  }
  EXPECT_EQ(one.pairsLowerWhenPaired, 3);
  const auto two = measureFitnessNoise(config, genomes, 3, 6, 5, 2);
  EXPECT_EQ(two.meanUnpairedVariance, one.meanUnpairedVariance);
}

}  // namespace
}  // namespace gpfd::experiments
