// What environments declare about themselves: parameter ranges that keep the integrators
// meaningful (refused with the parameter's name and range), typical state ranges, the default
// learner, and the afterstate game of Tetris.
#include <gtest/gtest.h>

#include <cmath>

#include "gpfd/env/afterstate_game.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

std::string refusal(const std::string& env, const Params& params) {
  try {
    Registry::global().make(env, params);
  } catch (const InputError& e) {
    return e.message();
  }
  return "accepted";
}

TEST(EnvParams, PhysicalParametersOutsideTheirRangesAreRefused) {
  EXPECT_EQ(refusal("acrobot", {{"dt", "1e300"}}),
            "dt must lie in [0.0001, 10], got 1e300 (acrobot.dt)");
  EXPECT_EQ(refusal("swimmer", {{"segments", "1000"}}),
            "segments must lie in [2, 100], got 1000 (swimmer.segments)");
  EXPECT_NE(refusal("cartpole", {{"gravity", "-9.8"}}), "accepted");
  EXPECT_NE(refusal("acrobot", {{"max_torque", "1e6"}}), "accepted");
  EXPECT_NE(refusal("swimmer", {{"viscosity", "1e4"}}), "accepted");
}

TEST(EnvParams, TheIntegrationStepIsBoundedTogetherWithWhatSetsIt) {
  // Acrobot: 0.2 s with rk4, 0.05 s with euler.
  EXPECT_NE(refusal("acrobot", {{"dt", "1"}}).find("(acrobot.substeps)"), std::string::npos);
  EXPECT_EQ(refusal("acrobot", {{"dt", "1"}, {"substeps", "5"}}), "accepted");
  EXPECT_NE(refusal("acrobot", {{"integrator", "euler"}}), "accepted");
  EXPECT_EQ(refusal("acrobot", {{"integrator", "euler"}, {"substeps", "4"}}), "accepted");
  // Cart-pole: 0.05 s.
  EXPECT_NE(refusal("cartpole", {{"dt", "0.1"}}), "accepted");
  EXPECT_EQ(refusal("cartpole", {{"dt", "0.1"}, {"substeps", "2"}}), "accepted");
  // Swimmer: h * segments * max(1, viscosity / 10) <= 0.2 (euler; 0.05 below viscosity 1), 0.3
  // (rk4).
  EXPECT_NE(refusal("swimmer", {{"segments", "30"}}).find("(swimmer.substeps)"), std::string::npos);
  EXPECT_EQ(refusal("swimmer", {{"segments", "30"}, {"substeps", "20"}}), "accepted");
  EXPECT_EQ(refusal("swimmer", {{"segments", "3"}, {"substeps", "1"}, {"integrator", "rk4"}}),
            "accepted");
  EXPECT_NE(refusal("swimmer", {{"segments", "4"}, {"substeps", "1"}, {"integrator", "rk4"}}),
            "accepted");
  EXPECT_NE(refusal("swimmer", {{"viscosity", "100"}, {"segments", "3"}}), "accepted");
  EXPECT_NE(refusal("swimmer", {{"viscosity", "0"}, {"segments", "8"}}), "accepted");
  EXPECT_EQ(refusal("swimmer", {{"viscosity", "0"}, {"segments", "8"}, {"substeps", "20"}}),
            "accepted");
}

// At the edge of every accepted range, random actions keep the state finite and within the
// velocity bounds the dynamics allow.
TEST(EnvParams, TheIntegratorsStayFiniteAtTheEdgeOfTheirRanges) {
  const std::vector<std::pair<std::string, Params>> edges{
      {"acrobot", {{"dt", "0.2"}, {"max_torque", "100"}}},
      {"acrobot", {{"dt", "0.2"}, {"substeps", "4"}, {"integrator", "euler"}}},
      {"cartpole", {{"dt", "0.05"}, {"max_force", "1000"}, {"integrator", "rk4"}}},
      {"cartpole", {{"dt", "0.05"}, {"gravity", "100"}}},
      {"swimmer", {{"segments", "20"}, {"horizon", "0"}}},
      {"swimmer", {{"segments", "40"}, {"substeps", "20"}, {"horizon", "0"}}},
      {"swimmer", {{"segments", "3"}, {"substeps", "1"}, {"integrator", "rk4"}}},
      {"swimmer", {{"segments", "4"}, {"viscosity", "100"}, {"substeps", "20"}}},
      {"swimmer", {{"segments", "8"}, {"viscosity", "0"}, {"substeps", "40"}}},
      {"swimmer", {{"max_torque", "100"}, {"horizon", "0"}}},
  };
  for (const auto& [name, params] : edges) {
    auto env = Registry::global().make(name, params);
    Rng rng(3);
    env->reset(rng);
    std::vector<double> action(env->actionSpace().components);
    double largest = 0.0;
    for (int t = 0; t < 300; ++t) {
      env->sampleAction(rng, action);
      const auto result = env->step(action);
      ASSERT_TRUE(std::isfinite(result.reward)) << name << " step " << t;
      for (double v : env->state()) {
        ASSERT_TRUE(std::isfinite(v)) << name << " step " << t;
        largest = std::max(largest, std::fabs(v));
      }
      if (result.terminated || result.truncated) env->reset(rng);
    }
    EXPECT_LT(largest, 1e3) << name;
  }
}

TEST(EnvKnowledge, TypicalStateRangesCoverTheStateWhereKnown) {
  for (const auto& name : Registry::global().names()) {
    const auto env = Registry::global().make(name);
    const auto ranges = env->typicalStateRanges();
    if (name == "tetris") {
      EXPECT_TRUE(ranges.empty());
      continue;
    }
    if (ranges.empty()) continue;  // An environment that knows none.
    ASSERT_EQ(ranges.size(), env->stateDim()) << name;
    for (const auto& r : ranges) EXPECT_LT(r.low, r.high) << name;
  }
  EXPECT_EQ(Registry::global().make("swimmer", {{"segments", "5"}})->typicalStateRanges().size(),
            12u);
}

TEST(EnvKnowledge, DefaultLearnersAndAfterstateGames) {
  for (const auto& name : Registry::global().names()) {
    const bool tetris = name == "tetris";
    EXPECT_EQ(Registry::global().info(name).defaultLearner, tetris ? "lpi" : "pg") << name;
    EXPECT_EQ(Registry::global().make(name)->afterstateGame() != nullptr, tetris) << name;
  }
}

TEST(EnvKnowledge, TetrisAfterstateGameMatchesItsPlacements) {
  Tetris tetris;
  AfterstateGame& game = *tetris.afterstateGame();
  Rng rng(5);
  tetris.reset(rng);
  for (int move = 0; move < 30 && !tetris.gameOver(); ++move) {
    TetrisAfterstates expected;
    tetris.afterstates(expected);
    const AfterstateView view = game.candidates();
    ASSERT_EQ(view.count, expected.placements.size());
    for (std::size_t i = 0; i < view.count; ++i) {
      EXPECT_EQ(view.rewards[i], expected.placements[i].rowsRemoved);
      EXPECT_EQ(view.ends[i] != 0, expected.placements[i].gameOver);
      for (std::size_t j = 0; j < expected.featureDim; ++j) {
        EXPECT_EQ(view.states[i * expected.featureDim + j], expected.featuresOf(i)[j]);
      }
    }
    const std::size_t pick = rng.below(view.count);
    if (view.ends[pick]) break;
    Tetris copy = tetris;
    const auto& p = expected.placements[pick];
    const double action[2] = {static_cast<double>(p.orientation), static_cast<double>(p.column)};
    copy.step(action);
    game.play(pick);
    ASSERT_EQ(std::vector<double>(tetris.state().begin(), tetris.state().end() - 1),
              std::vector<double>(copy.state().begin(), copy.state().end() - 1));
  }
}

TEST(EnvKnowledge, TetrisKnowsBertsekasIoffeWeightsForTheirLayoutOnly) {
  EXPECT_TRUE(Tetris().knownValueWeights().empty());
  const Tetris bertsekas(TetrisConfig::fromParams({{"state", "bertsekas"}, {"cols", "10"}}));
  const auto w = bertsekas.knownValueWeights();
  ASSERT_EQ(w.size(), bertsekas.stateDim());
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double expected = i == 19 ? -10.0 : i == 20 ? -1.0 : 0.0;  // Max height, holes.
    EXPECT_EQ(w[i], expected) << i;
  }
}

}  // namespace
}  // namespace gpfd::env
