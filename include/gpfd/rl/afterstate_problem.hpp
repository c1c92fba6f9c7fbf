// rl: the view of a game that lambda-policy iteration needs: at each decision, every candidate
// move with the variables of the state it leads to (the afterstate), its reward and whether it
// ends the game. Tetris provides one (tetris_afterstates.hpp); tests provide tiny ones.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpfd/util/rng.hpp"

namespace gpfd::rl {

// The candidates of the current decision. Pointers stay valid until the next non-const call on
// the problem.
struct AfterstateView {
  std::size_t count = 0;               // 0: no move is possible (the game is over).
  const double* states = nullptr;      // count x stateDim(), row-major.
  const double* rewards = nullptr;     // count values.
  const std::uint8_t* ends = nullptr;  // count flags: 1 when the move ends the game.
};

class AfterstateProblem {
 public:
  virtual ~AfterstateProblem() = default;
  virtual std::size_t stateDim() const = 0;
  // Starts a game; all randomness of the game (e.g. the pieces) is drawn from `rng`, here or in
  // choose().
  virtual void reset(Rng& rng) = 0;
  virtual AfterstateView candidates() = 0;
  // Plays candidate `index` of the current view (a move that does not end the game).
  virtual void choose(std::size_t index, Rng& rng) = 0;
};

}  // namespace gpfd::rl
