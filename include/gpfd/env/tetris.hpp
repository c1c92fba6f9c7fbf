// env: Tetris as in the paper (12 x 8 board, 7 tetrominoes drawn uniformly), with the afterstates
// that lambda-policy iteration needs and the Bertsekas-Ioffe feature set.
#pragma once

#include <vector>

#include "gpfd/env/afterstate_game.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/env/tetris_board.hpp"

namespace gpfd::env {

struct TetrisConfig {
  int rows = 12;  // The paper: 12 x 8; the literature's standard: 20 x 10.
  int cols = 8;
  TetrisFeatures state = TetrisFeatures::Paper;
  int maxSteps = 0;  // Truncation after this many pieces; 0 = none (ours).

  // The parameters, declared once: names, defaults, ranges and meanings.
  static const ParamTable<TetrisConfig>& table();
  static TetrisConfig fromParams(const Params& params) { return table().read(params); }
};

// One legal placement of the current piece and what it leads to.
struct TetrisPlacement {
  int orientation = 0;
  int column = 0;       // Leftmost column of the piece.
  int rowsRemoved = 0;  // The reward of this placement.
  bool gameOver = false;
};

// All placements of the current piece; features holds placements.size() rows of featureDim
// values: the state variables of the board after the placement (in the environment's `state`
// layout; for the paper's layout the last value is the piece just placed, since the next one is
// not yet drawn).
struct TetrisAfterstates {
  std::vector<TetrisPlacement> placements;
  std::vector<double> features;
  std::size_t featureDim = 0;

  std::span<const double> featuresOf(std::size_t i) const {
    return {features.data() + i * featureDim, featureDim};
  }
};

// State: the 2c + 2 variables of `state` (TetrisFeatures). Action: (orientation, column), an
// orientation index of orientationsOf(piece()) and the piece's leftmost column (choices 4 x c,
// of which the piece's placements are legal). Reward: rows
// removed. The next piece is drawn from an engine seeded by reset(). After game over, step()
// changes nothing and reports terminated with reward 0. Learned with lambda-policy iteration over
// its afterstates (AfterstateGame).
class Tetris final : public Environment, public AfterstateGame {
 public:
  explicit Tetris(TetrisConfig config = {});
  static EnvInfo info();  // Name, description, factory and default learner, for the registry.

  std::string name() const override { return "tetris"; }
  Params params() const override { return TetrisConfig::table().write(config_); }
  const std::vector<std::string>& stateNames() const override { return names_; }
  ActionSpace actionSpace() const override;
  void reset(Rng& rng) override;
  std::span<const double> state() const override { return state_; }
  // The state variables do not determine a board: this builds the canonical board that has them
  // (columns filled up to their heights, the holes carved from the bottom row up, left to right)
  // and throws InputError when no board has them. Bertsekas layout: the piece is kept.
  void setState(std::span<const double> state) override;
  StepResult step(std::span<const double> action) override;
  void sampleAction(Rng& rng, std::span<double> action) const override;
  // The legal actions are the current piece's placements: orientation (of the 4 that a piece has
  // at most) x column.
  bool hasStateDependentActions() const override { return true; }
  void legalActionMask(std::span<std::uint8_t> mask) const override;
  // The orientation taken modulo the piece's orientation count, the column clipped to where that
  // orientation fits.
  void nearestLegalAction(std::span<const double> action, std::span<double> legal) const override;
  // The board (hidden rows included), the piece, the piece generator, game over and the step
  // count.
  std::vector<std::uint64_t> snapshot() const override;
  void restore(std::span<const std::uint64_t> words) override;
  AfterstateGame* afterstateGame() override { return this; }

  // AfterstateGame: every placement of the current piece.
  AfterstateView candidates() override;
  StepResult play(std::size_t index) override;
  // In the Bertsekas layout, Bertsekas & Ioffe's (1996) hand-tuned start: all 0 except max
  // height -10 and holes -1. None in the paper's layout.
  std::vector<double> knownValueWeights() const override;

  const TetrisConfig& config() const { return config_; }
  const TetrisBoard& board() const { return board_; }
  int piece() const { return piece_; }
  bool gameOver() const { return gameOver_; }
  // Sets the board and the current piece exactly (tests, replays); the board must have the
  // configured size.
  void setBoard(const TetrisBoard& board, int piece);
  // Every legal placement of the current piece, with its afterstate (reuses `out`'s storage):
  // in bulk, from the current column heights and holes updated per placement
  // (tetris_bulk_afterstates.cpp); the same values as afterstatesReference, which drops the piece
  // on a copy of the board for each placement and scans the result.
  void afterstates(TetrisAfterstates& out) const;
  void afterstatesReference(TetrisAfterstates& out) const;
  // candidates() computes in bulk (the default) or, with false, by afterstatesReference (tests and
  // benchmarks compare the two; the values are the same).
  void setBulkAfterstates(bool bulk) { bulkAfterstates_ = bulk; }
  // Throws InputError unless (orientation, column) is a legal placement of the current piece.
  void checkAction(std::span<const double> action) const;

 private:
  void refreshState();

  TetrisConfig config_;
  std::vector<std::string> names_;
  TetrisBoard board_;
  Rng pieces_;
  int piece_ = 0;
  bool gameOver_ = false;
  int steps_ = 0;
  std::vector<double> state_;
  bool bulkAfterstates_ = true;
  // The last candidates(): placements with their rewards and game-over flags.
  TetrisAfterstates afterstates_;
  std::vector<double> rewards_;
  std::vector<std::uint8_t> ends_;
};

}  // namespace gpfd::env
