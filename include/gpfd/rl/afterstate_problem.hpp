// rl: the view of a game that lambda-policy iteration needs: at each decision, every candidate
// move with the variables of the state it leads to (the afterstate), its reward and whether it
// ends the game. An environment's AfterstateGame provides one (game_afterstates.hpp); tests
// provide tiny ones.
#pragma once

#include <cstddef>

#include "gpfd/env/afterstate_game.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::rl {

using env::AfterstateView;

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
