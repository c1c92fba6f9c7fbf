// Tetris: pieces and orientations, the drop rule, line clears, game over, state variables, the
// Bertsekas-Ioffe features, afterstates and seeding.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "gpfd/env/tetris.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

using Shape = std::set<std::pair<int, int>>;

Shape shapeOf(const Orientation& o) {
  Shape s;
  for (const auto& [x, y] : o.cells) s.insert({x, y});
  return s;
}

Shape normalised(const Shape& s) {
  int mx = 1 << 20, my = 1 << 20;
  for (const auto& [x, y] : s) mx = std::min(mx, x), my = std::min(my, y);
  Shape out;
  for (const auto& [x, y] : s) out.insert({x - mx, y - my});
  return out;
}

TEST(Tetromino, OrientationsAreTheDistinctRotationsOfEachPiece) {
  const std::array<int, 7> expected{2, 1, 4, 2, 2, 4, 4};
  for (int p = 0; p < kPieceCount; ++p) {
    const auto orientations = orientationsOf(p);
    ASSERT_EQ(static_cast<int>(orientations.size()), expected[static_cast<std::size_t>(p)]);
    std::set<Shape> all;
    for (const auto& o : orientations) all.insert(shapeOf(o));
    EXPECT_EQ(all.size(), orientations.size()) << "duplicate orientation of " << kPieceLetters[p];
    for (const auto& o : orientations) {
      EXPECT_EQ(normalised(shapeOf(o)), shapeOf(o));
      Shape turned;  // (x, y) -> (y, -x)
      for (const auto& [x, y] : shapeOf(o)) turned.insert({y, -x});
      EXPECT_TRUE(all.count(normalised(turned))) << kPieceLetters[p];
    }
  }
}

TEST(Tetromino, PlacementCountsOnEightColumns) {
  const std::array<int, 7> expected{13, 7, 26, 13, 13, 26, 26};
  for (int p = 0; p < kPieceCount; ++p) EXPECT_EQ(placementCount(p, 8), expected[p]);
}

TetrisBoard board(const std::vector<std::string>& rows) { return TetrisBoard::fromText(rows); }

std::vector<std::string> emptyRows(int rows, int cols) {
  return std::vector<std::string>(static_cast<std::size_t>(rows), std::string(cols, '.'));
}

TEST(TetrisBoard, EveryPieceAndOrientationOnAnEmptyBoardRestsOnTheFloor) {
  for (int p = 0; p < kPieceCount; ++p) {
    const auto orientations = orientationsOf(p);
    for (std::size_t o = 0; o < orientations.size(); ++o) {
      for (int c = 0; c + orientations[o].width <= 8; ++c) {
        TetrisBoard b(12, 8);
        const DropOutcome out = b.drop(p, static_cast<int>(o), c);
        EXPECT_EQ(out.rowsRemoved, 0);
        EXPECT_FALSE(out.gameOver);
        Shape filled;
        for (int r = 0; r < 12; ++r) {
          for (int x = 0; x < 8; ++x) {
            if (b.filled(r, x)) filled.insert({x - c, r});
          }
        }
        EXPECT_EQ(filled, shapeOf(orientations[o])) << kPieceLetters[p] << o << " at " << c;
      }
    }
  }
}

TEST(TetrisBoard, PiecesRestOnTheHighestCellUnderThemWithoutSliding) {
  // Column heights 0,3,1,0,... with an overhang: a flat I on columns 0-3 rests at row 3.
  auto b = board({"........", "........", "........", "........", "........", "........",
                  "........", "........", "........", ".#......", ".#......", ".##....."});
  b.drop(0, 0, 0);
  EXPECT_EQ(b.toText()[8], "####....");
  // The I now covers empty cells: 3 in column 0, 2 in column 2 and 3 in column 3.
  EXPECT_EQ(b.holes(), 8);
}

TEST(TetrisBoard, EveryOrientationOnACraftedBoard) {
  // Heights 2,0,1,3,0,0,2,1. Check the landing row of each placement against the rule
  // base = max over the piece's columns of (height - bottom offset).
  const auto rows = std::vector<std::string>{"........", "........", "........", "........",
                                             "........", "........", "........", "........",
                                             "........", "...#....", "#..#..#.", "#.##..##"};
  const std::array<int, 8> heights{2, 0, 1, 3, 0, 0, 2, 1};
  for (int p = 0; p < kPieceCount; ++p) {
    const auto orientations = orientationsOf(p);
    for (std::size_t o = 0; o < orientations.size(); ++o) {
      const Orientation& shape = orientations[o];
      for (int c = 0; c + shape.width <= 8; ++c) {
        auto b = board(rows);
        b.drop(p, static_cast<int>(o), c);
        int base = 0;
        for (int x = 0; x < shape.width; ++x) {
          base = std::max(base, heights[static_cast<std::size_t>(c + x)] - shape.bottom[x]);
        }
        auto want = board(rows);
        for (const auto& [x, y] : shape.cells) {
          ASSERT_FALSE(want.filled(base + y, c + x));
          want.set(base + y, c + x, true);
        }
        EXPECT_EQ(b, want) << kPieceLetters[p] << o << " at " << c;
        // It touches something: the floor or a filled cell right below one of its cells.
        bool supported = false;
        for (const auto& [x, y] : shape.cells) {
          supported = supported || base + y == 0 || board(rows).filled(base + y - 1, c + x);
        }
        EXPECT_TRUE(supported);
      }
    }
  }
}

TEST(TetrisBoard, ClearsOneAndTwoLines) {
  auto rows = emptyRows(12, 8);
  rows[11] = "###.####";
  auto b = board(rows);
  EXPECT_EQ(b.drop(0, 1, 3).rowsRemoved, 1);  // Vertical I into the well.
  EXPECT_EQ(b.height(3), 3);
  EXPECT_EQ(b.height(0), 0);
  rows[10] = "######..";
  rows[11] = "######..";
  auto two = board(rows);
  const DropOutcome out = two.drop(1, 0, 6);  // O fills both gaps.
  EXPECT_EQ(out.rowsRemoved, 2);
  EXPECT_EQ(two, TetrisBoard(12, 8));
  // Two full rows with a partial one between them: the partial row drops by one.
  rows = emptyRows(12, 8);
  rows[9] = "#######.";
  rows[10] = "####.##.";
  rows[11] = "#######.";
  auto split = board(rows);
  EXPECT_EQ(split.drop(0, 1, 7).rowsRemoved, 2);
  EXPECT_EQ(split.toText()[11], "####.###");
  EXPECT_EQ(split.toText()[10], ".......#");
}

TEST(TetrisBoard, GameOverWhenAColumnStillExceedsTheTop) {
  auto rows = emptyRows(12, 8);
  for (int r = 2; r < 12; ++r) rows[static_cast<std::size_t>(r)] = "#.......";
  auto b = board(rows);
  EXPECT_TRUE(b.drop(0, 1, 0).gameOver);  // Height 10 + 4 > 12.
  auto ok = board(rows);
  EXPECT_FALSE(ok.drop(1, 0, 1).gameOver);
  // A piece that overflows the top but completes rows: they are removed first, the game goes on.
  for (int i = 0; i < 12; ++i) rows[static_cast<std::size_t>(i)] = i < 3 ? ".#######" : "#.######";
  auto clears = board(rows);
  const DropOutcome out = clears.drop(0, 1, 0);  // Vertical I on column 0, rows 10-13 (1-based).
  EXPECT_EQ(out.rowsRemoved, 3);
  EXPECT_FALSE(out.gameOver);
  EXPECT_EQ(clears.height(0), 10);
}

TEST(TetrisBoard, StateVariablesOnACraftedBoard) {
  const auto b = board({"........", "........", "........", "........", "........", "........",
                        "........", "...#....", "...#..#.", "#.....#.", "#..#.#..", "##.#####"});
  std::vector<double> paper(18), bi(18);
  b.features(TetrisFeatures::Paper, 4, paper.data());
  b.features(TetrisFeatures::Bertsekas, 4, bi.data());
  const std::vector<double> heights{3, 1, 0, 5, 1, 2, 4, 1};
  const std::vector<double> diffs{2, 1, 5, 4, 1, 2, 3};
  // Holes: row 3 (1-based) of column 4 and row 2 of column 7.
  std::vector<double> want = heights;
  want.insert(want.end(), diffs.begin(), diffs.end());
  want.push_back(5);
  want.push_back(2);
  want.push_back(4);
  EXPECT_EQ(paper, want);
  want.back() = 1.0;
  EXPECT_EQ(bi, want);
  EXPECT_EQ(b.holes(), 2);
}

TEST(TetrisBoard, BertsekasFeatureCountOnTenColumns) {
  EXPECT_EQ(tetrisFeatureCount(10), 22);
  EXPECT_EQ(tetrisFeatureCount(8), 18);
  Tetris t(TetrisConfig::fromParams({{"rows", "20"}, {"cols", "10"}, {"state", "bertsekas"}}));
  EXPECT_EQ(t.stateDim(), 22u);
  EXPECT_EQ(t.stateNames().back(), "const");
  EXPECT_EQ(t.state().back(), 1.0);
}

TEST(Tetris, AfterstatesListEveryPlacementWithItsOutcome) {
  Tetris t;
  auto rows = emptyRows(12, 8);
  rows[11] = "####.###";
  rows[10] = "####.###";
  TetrisAfterstates after;
  for (int p = 0; p < kPieceCount; ++p) {
    t.setBoard(TetrisBoard::fromText(rows), p);
    t.afterstates(after);
    ASSERT_EQ(static_cast<int>(after.placements.size()), placementCount(p, 8));
    ASSERT_EQ(after.featureDim, 18u);
    for (std::size_t i = 0; i < after.placements.size(); ++i) {
      const TetrisPlacement& pl = after.placements[i];
      auto b = TetrisBoard::fromText(rows);
      const DropOutcome out = b.drop(p, pl.orientation, pl.column);
      EXPECT_EQ(pl.rowsRemoved, out.rowsRemoved);
      EXPECT_EQ(pl.gameOver, out.gameOver);
      std::vector<double> f(18);
      b.features(TetrisFeatures::Paper, p, f.data());
      EXPECT_TRUE(std::equal(f.begin(), f.end(), after.featuresOf(i).begin()));
      // step() with the same action reaches the same board and reward.
      Tetris s;
      s.setBoard(TetrisBoard::fromText(rows), p);
      const StepResult r = s.step(std::vector<double>{double(pl.orientation), double(pl.column)});
      EXPECT_EQ(r.reward, pl.rowsRemoved);
      EXPECT_EQ(s.board(), b);
    }
  }
  t.setBoard(TetrisBoard::fromText(rows), 0);  // Vertical I in the well clears two rows.
  t.afterstates(after);
  int best = 0;
  for (const auto& pl : after.placements) best = std::max(best, pl.rowsRemoved);
  EXPECT_EQ(best, 2);
}

TEST(Tetris, RejectsIllegalActionsAndStopsAfterGameOver) {
  Tetris t;
  t.setBoard(TetrisBoard(12, 8), 1);  // O: one orientation, columns 0..6.
  EXPECT_THROW(t.step(std::vector<double>{1, 0}), InputError);
  EXPECT_THROW(t.step(std::vector<double>{0, 7}), InputError);
  EXPECT_THROW(t.step(std::vector<double>{0, 0.5}), InputError);
  EXPECT_THROW(t.step(std::vector<double>{0}), InputError);
  StepResult r;
  int pieces = 0;
  while (!r.terminated) {
    t.setBoard(t.board(), 1);
    r = t.step(std::vector<double>{0, 0});  // Stack O pieces in one place.
    ++pieces;
  }
  EXPECT_EQ(pieces, 7);  // 6 x 2 = 12 rows fit; the 7th overflows.
  const auto before = t.board();
  r = t.step(std::vector<double>{0, 0});
  EXPECT_TRUE(r.terminated);
  EXPECT_EQ(r.reward, 0.0);
  EXPECT_EQ(t.board(), before);
}

TEST(Tetris, SetStateBuildsTheCanonicalBoard) {
  Tetris t;
  const std::vector<double> s{3, 1, 0, 5, 1, 2, 4, 1, 2, 1, 5, 4, 1, 2, 3, 5, 4, 6};
  t.setState(s);
  EXPECT_TRUE(std::equal(s.begin(), s.end(), t.state().begin()));
  EXPECT_EQ(t.piece(), 6);
  auto bad = s;
  bad[8] = 1;  // |h1 - h2| is 2.
  EXPECT_THROW(t.setState(bad), InputError);
  bad = s;
  bad[16] = 100;  // Too many holes for these heights.
  EXPECT_THROW(t.setState(bad), InputError);
  bad = s;
  bad[17] = 7;
  EXPECT_THROW(t.setState(bad), InputError);
}

TEST(Tetris, PiecesAreUniformAndSeeded) {
  const auto play = [](std::uint64_t seed) {
    Tetris t(TetrisConfig::fromParams({{"rows", "20"}, {"cols", "10"}}));
    Rng rng(seed);
    t.reset(rng);
    std::vector<double> trace;
    std::vector<double> action(2);
    for (int i = 0; i < 200; ++i) {
      t.sampleAction(rng, action);
      const StepResult r = t.step(action);
      trace.insert(trace.end(), t.state().begin(), t.state().end());
      if (r.terminated) t.reset(rng);
    }
    return trace;
  };
  EXPECT_EQ(play(3), play(3));
  EXPECT_NE(play(3), play(4));
  Tetris t;
  Rng rng(9);
  std::array<int, 7> counts{};
  for (int i = 0; i < 7000; ++i) {
    t.reset(rng);
    ++counts[static_cast<std::size_t>(t.piece())];
  }
  for (int c : counts) EXPECT_NEAR(c, 1000, 150);
}

}  // namespace
}  // namespace gpfd::env
