// rl: an environment's afterstate game (env::AfterstateGame) seen as the AfterstateProblem that
// lambda-policy iteration plays.
#pragma once

#include "gpfd/env/afterstate_game.hpp"
#include "gpfd/rl/afterstate_problem.hpp"

namespace gpfd::rl {

// Wraps an environment and its afterstate game (both not owned; they must outlive this).
class GameAfterstateProblem final : public AfterstateProblem {
 public:
  GameAfterstateProblem(env::Environment& env, env::AfterstateGame& game)
      : env_(&env), game_(&game) {}

  std::size_t stateDim() const override { return env_->stateDim(); }
  void reset(Rng& rng) override { env_->reset(rng); }
  AfterstateView candidates() override { return game_->candidates(); }
  void choose(std::size_t index, Rng&) override { game_->play(index); }

 private:
  env::Environment* env_;
  env::AfterstateGame* game_;
};

}  // namespace gpfd::rl
