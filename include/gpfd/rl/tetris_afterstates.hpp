// rl: Tetris seen as an afterstate problem for lambda-policy iteration, and the known-good
// starting weights of the Bertsekas-Ioffe features.
#pragma once

#include <cstdint>
#include <vector>

#include "gpfd/env/tetris.hpp"
#include "gpfd/rl/afterstate_problem.hpp"

namespace gpfd::rl {

// Wraps a Tetris instance (not owned; it must outlive this). The candidates are every legal
// placement of the current piece with the state variables of the board after it, computed in bulk
// (Tetris::afterstates) or, with `bulk` false, placement by placement (the reference; the same
// values).
class TetrisAfterstateProblem final : public AfterstateProblem {
 public:
  explicit TetrisAfterstateProblem(env::Tetris& tetris, bool bulk = true)
      : tetris_(&tetris), bulk_(bulk) {}

  std::size_t stateDim() const override { return tetris_->stateDim(); }
  void reset(Rng& rng) override { tetris_->reset(rng); }
  AfterstateView candidates() override;
  void choose(std::size_t index, Rng& rng) override;

 private:
  env::Tetris* tetris_;
  bool bulk_;
  env::TetrisAfterstates afterstates_;
  std::vector<double> rewards_;
  std::vector<std::uint8_t> ends_;
};

// Bertsekas & Ioffe's (1996) hand-tuned start over a Tetris state of `cols` columns (both
// layouts: c heights, c-1 differences, max height, holes, last value): all 0 except
// max height -10 and holes -1. `extra` zeros are appended (e.g. 1 for a bias feature).
std::vector<double> bertsekasIoffeStartWeights(int cols, std::size_t extra = 0);

}  // namespace gpfd::rl
