// env: the afterstate view of a game: at each decision, every legal move with the state variables
// of the position it leads to (its afterstate), its reward, and whether it ends the game. Learners
// that choose moves by the value of afterstates (lambda-policy iteration) ask an environment for
// it with Environment::afterstateGame() instead of knowing its type.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gpfd/env/environment.hpp"

namespace gpfd::env {

// The candidates of the current decision. Pointers stay valid until the next non-const call.
struct AfterstateView {
  std::size_t count = 0;               // 0: no move is possible (the game is over).
  const double* states = nullptr;      // count x stateDim() afterstate variables, row-major.
  const double* rewards = nullptr;     // count values.
  const std::uint8_t* ends = nullptr;  // count flags: 1 when the move ends the game.
};

class AfterstateGame {
 public:
  virtual ~AfterstateGame() = default;
  // Every legal move of the current position.
  virtual AfterstateView candidates() = 0;
  // Plays candidate `index` of the last candidates(), as step() with that move's action would.
  virtual StepResult play(std::size_t index) = 0;
  // Weights of a value function linear in the state variables (one per variable) that is known to
  // play well, as a start for learners; empty when none is known.
  virtual std::vector<double> knownValueWeights() const { return {}; }
};

}  // namespace gpfd::env
