// The action space says what a front needs to drive an environment without knowing its type: the
// choices of each discrete component, whether the legal actions depend on the state, which are
// legal now, and the legal action nearest to any other.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/env/tetromino.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

std::vector<std::uint8_t> maskOf(const Environment& env) {
  std::vector<std::uint8_t> mask(env.actionSpace().discreteActions(), 0);
  env.legalActionMask(mask);
  return mask;
}

TEST(ActionSpace, ChoicesPerComponent) {
  const auto cartpole = Registry::global().make("cartpole", {{"actions", "discrete"}});
  EXPECT_EQ(cartpole->actionSpace().choices, std::vector<int>{2});
  EXPECT_EQ(cartpole->actionSpace().discreteActions(), 2U);
  const auto acrobot = Registry::global().make("acrobot", {{"actions", "discrete"}});
  EXPECT_EQ(acrobot->actionSpace().choices, std::vector<int>{3});
  const auto tetris = Registry::global().make("tetris", {{"cols", "6"}});
  const ActionSpace space = tetris->actionSpace();
  EXPECT_EQ(space.choices, (std::vector<int>{4, 6}));  // Orientations, columns.
  EXPECT_EQ(space.components, 2U);
  EXPECT_EQ(space.discreteActions(), 24U);
  const auto continuous = Registry::global().make("cartpole");
  EXPECT_TRUE(continuous->actionSpace().choices.empty());
  EXPECT_EQ(continuous->actionSpace().discreteActions(), 0U);
}

TEST(ActionSpace, FixedChoicesAreAllLegalAndKeptAsGiven) {
  const auto cartpole = Registry::global().make("cartpole", {{"actions", "discrete"}});
  EXPECT_FALSE(cartpole->hasStateDependentActions());
  EXPECT_EQ(maskOf(*cartpole), (std::vector<std::uint8_t>{1, 1}));
  std::vector<double> legal(1, -1.0);
  cartpole->nearestLegalAction(std::vector<double>{1.0}, legal);
  EXPECT_EQ(legal[0], 1.0);
}

TEST(ActionSpace, TetrisMasksEachPiecesPlacements) {
  Tetris tetris;
  EXPECT_TRUE(tetris.hasStateDependentActions());
  const int cols = tetris.config().cols;
  for (int piece = 0; piece < kPieceCount; ++piece) {
    tetris.setBoard(TetrisBoard(12, cols), piece);
    const auto mask = maskOf(tetris);
    int legal = 0;
    for (int o = 0; o < 4; ++o) {
      for (int c = 0; c < cols; ++c) {
        const bool isLegal = mask[static_cast<std::size_t>(o * cols + c)] != 0;
        legal += isLegal ? 1 : 0;
        const std::vector<double> action{static_cast<double>(o), static_cast<double>(c)};
        if (isLegal) {
          EXPECT_NO_THROW(tetris.checkAction(action)) << piece << " " << o << " " << c;
        } else {
          EXPECT_THROW(tetris.checkAction(action), InputError) << piece << " " << o << " " << c;
        }
      }
    }
    EXPECT_EQ(legal, placementCount(piece, cols)) << piece;
  }
}

TEST(ActionSpace, TetrisMapsAnActionToTheNearestLegalPlacement) {
  Tetris tetris;
  tetris.setBoard(TetrisBoard(12, 8), 1);  // O: one orientation, width 2, columns 0..6.
  std::vector<double> legal(2);
  tetris.nearestLegalAction(std::vector<double>{3, 7}, legal);
  EXPECT_EQ(legal, (std::vector<double>{0, 6}));  // Orientation modulo 1; the column clipped.
  tetris.setBoard(TetrisBoard(12, 8), 0);         // I: two orientations.
  const auto i = orientationsOf(0);
  tetris.nearestLegalAction(std::vector<double>{2, 7}, legal);
  EXPECT_EQ(legal, (std::vector<double>{0, 8.0 - i[0].width}));
  tetris.nearestLegalAction(std::vector<double>{5, 7}, legal);
  EXPECT_EQ(legal, (std::vector<double>{1, 8.0 - i[1].width}));
  tetris.nearestLegalAction(std::vector<double>{1, 2}, legal);  // Legal already: kept.
  EXPECT_EQ(legal, (std::vector<double>{1, 2}));
}

}  // namespace
}  // namespace gpfd::env
