// Lambda-policy iteration on Tetris decides the same with afterstates computed in bulk as with the
// reference (one drop per placement): the same curves and weights, bit for bit, with the raw
// variables, and with compiled features beside them (normalised or not).
#include <gtest/gtest.h>

#include <bit>
#include <memory>

#include "gpfd/env/tetris.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/rl/game_afterstates.hpp"
#include "gpfd/rl/lambda_policy_iteration.hpp"

namespace gpfd::rl {
namespace {

LearningCurve train(bool bulk, const features::FeatureMap& map, bool normalise,
                    std::uint64_t seed) {
  env::Tetris tetris(env::TetrisConfig::fromParams({{"state", "bertsekas"}}));
  tetris.setBulkAfterstates(bulk);
  GameAfterstateProblem problem(tetris, tetris);
  LambdaPolicyIterationConfig config;
  config.iterations = 4;
  config.gamesPerIteration = 6;
  config.maxMovesPerGame = 400;
  config.features.normalise = normalise;
  if (map.outputDim() == tetris.stateDim()) {
    config.initialWeights = tetris.knownValueWeights();
    config.initialWeights.push_back(0.0);  // The bias.
  }
  Rng rng(seed);
  return trainLambdaPolicyIteration(problem, map, config, rng);
}

void expectSame(const LearningCurve& a, const LearningCurve& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].steps, b.points[i].steps) << "row " << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.points[i].meanReturn),
              std::bit_cast<std::uint64_t>(b.points[i].meanReturn));
  }
  EXPECT_EQ(a.weights.values, b.weights.values);
  EXPECT_EQ(a.diverged, b.diverged);
}

TEST(TetrisBulk, LambdaPolicyIterationDecidesTheSameWithBulkAfterstates) {
  const features::RawFeatureMap raw(18);
  const LearningCurve bulk = train(true, raw, false, 8), reference = train(false, raw, false, 8);
  EXPECT_GT(reference.steps, 500);
  expectSame(bulk, reference);

  env::Tetris tetris;
  const auto file = expr::parseFeaturesFile("max(holes, h3) / (max_height + 1)\nd2 * d5\n", "test",
                                            tetris.stateNames(), "tetris");
  const auto compiled = std::make_shared<jit::CompiledFeatureMap>(file.genome, 18);
  const features::ConcatFeatureMap both({compiled, std::make_shared<features::RawFeatureMap>(18)});
  for (const bool normalise : {false, true}) {
    SCOPED_TRACE(normalise);
    expectSame(train(true, both, normalise, 3), train(false, both, normalise, 3));
  }
}

}  // namespace
}  // namespace gpfd::rl
