// Tetris afterstates in bulk equal the reference (a drop on a copy of the board per placement):
// the same placements, rewards, game-over flags and state variables, on random boards of every
// size limit, boards with rows about to be removed, boards near the top, boards with cells above
// the visible rows, both state layouts, and along random games.
#include <gtest/gtest.h>

#include "gpfd/env/tetris.hpp"

namespace gpfd::env {
namespace {

void expectSameAfterstates(const Tetris& tetris) {
  TetrisAfterstates bulk, reference;
  bulk.features.assign(3, -1.0);  // Stale contents must not leak through.
  tetris.afterstates(bulk);
  tetris.afterstatesReference(reference);
  ASSERT_EQ(bulk.featureDim, reference.featureDim);
  ASSERT_EQ(bulk.placements.size(), reference.placements.size());
  for (std::size_t i = 0; i < bulk.placements.size(); ++i) {
    const TetrisPlacement &a = bulk.placements[i], &b = reference.placements[i];
    ASSERT_EQ(a.orientation, b.orientation);
    ASSERT_EQ(a.column, b.column);
    ASSERT_EQ(a.rowsRemoved, b.rowsRemoved) << "placement " << i;
    ASSERT_EQ(a.gameOver, b.gameOver) << "placement " << i;
  }
  ASSERT_EQ(bulk.features, reference.features) << "piece " << tetris.piece();
}

// A random board: columns filled to random heights, then cells removed at random (holes), some
// rows made full or full but one cell.
TetrisBoard randomBoard(int rows, int cols, Rng& rng, int hiddenCells) {
  TetrisBoard board(rows, cols);
  const int peak = static_cast<int>(rng.below(static_cast<std::uint64_t>(rows) + 1));
  for (int c = 0; c < cols; ++c) {
    const int h = static_cast<int>(rng.below(static_cast<std::uint64_t>(peak) + 1));
    for (int r = 0; r < h; ++r) board.set(r, c, !rng.bernoulli(0.15));
  }
  for (int k = 0; k < 3; ++k) {
    const int r = static_cast<int>(rng.below(static_cast<std::uint64_t>(std::max(peak, 1))));
    for (int c = 0; c < cols; ++c) board.set(r, c, true);
    if (rng.bernoulli(0.6)) board.set(r, static_cast<int>(rng.below(cols)), false);
  }
  for (int k = 0; k < hiddenCells; ++k) {
    board.set(rows + static_cast<int>(rng.below(4)), static_cast<int>(rng.below(cols)), true);
  }
  return board;
}

TEST(TetrisBulk, AfterstatesEqualTheReferenceOnRandomBoards) {
  Rng rng(12);
  const std::vector<std::pair<int, int>> sizes{{12, 8}, {20, 10}, {4, 4}, {60, 30}, {7, 5}};
  for (const auto& [rows, cols] : sizes) {
    for (const TetrisFeatures kind : {TetrisFeatures::Paper, TetrisFeatures::Bertsekas}) {
      Tetris tetris(TetrisConfig{.rows = rows, .cols = cols, .state = kind});
      for (int trial = 0; trial < 300; ++trial) {
        const int hidden = trial % 25 == 0 ? 2 : 0;
        for (int piece = 0; piece < kPieceCount; ++piece) {
          tetris.setBoard(randomBoard(rows, cols, rng, hidden), piece);
          SCOPED_TRACE(testing::Message() << rows << "x" << cols << " trial " << trial);
          expectSameAfterstates(tetris);
        }
      }
    }
  }
}

// Games played by a simple heuristic (fewest holes, then lowest stack), so that they last and
// remove rows.
TEST(TetrisBulk, AfterstatesEqualTheReferenceAlongGames) {
  Tetris tetris;
  Rng rng(4);
  TetrisAfterstates options;
  int decisions = 0, rows = 0;
  for (int game = 0; game < 20; ++game) {
    tetris.reset(rng);
    while (!tetris.gameOver() && decisions < 5000 * (game + 1)) {
      expectSameAfterstates(tetris);
      ++decisions;
      tetris.afterstatesReference(options);
      std::size_t best = 0;
      double bestScore = 1e300;
      for (std::size_t i = 0; i < options.placements.size(); ++i) {
        const auto f = options.featuresOf(i);
        const double score = 4.0 * f[16] + f[15] - 10.0 * options.placements[i].rowsRemoved +
                             (options.placements[i].gameOver ? 1e6 : 0.0) + 0.01 * rng.uniform();
        if (score < bestScore) bestScore = score, best = i;
      }
      const double action[2] = {static_cast<double>(options.placements[best].orientation),
                                static_cast<double>(options.placements[best].column)};
      rows += static_cast<int>(tetris.step(action).reward);
    }
  }
  EXPECT_GT(decisions, 600);
  EXPECT_GT(rows, 150);
}

}  // namespace
}  // namespace gpfd::env
