#include "gpfd/rl/tetris_afterstates.hpp"

namespace gpfd::rl {

AfterstateView TetrisAfterstateProblem::candidates() {
  if (tetris_->gameOver()) return {};
  if (bulk_) {
    tetris_->afterstates(afterstates_);
  } else {
    tetris_->afterstatesReference(afterstates_);
  }
  const std::size_t n = afterstates_.placements.size();
  rewards_.resize(n);
  ends_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    rewards_[i] = afterstates_.placements[i].rowsRemoved;
    ends_[i] = afterstates_.placements[i].gameOver ? 1 : 0;
  }
  return {n, afterstates_.features.data(), rewards_.data(), ends_.data()};
}

void TetrisAfterstateProblem::choose(std::size_t index, Rng&) {
  const env::TetrisPlacement& p = afterstates_.placements[index];
  const double action[2] = {static_cast<double>(p.orientation), static_cast<double>(p.column)};
  tetris_->step(action);
}

std::vector<double> bertsekasIoffeStartWeights(int cols, std::size_t extra) {
  std::vector<double> w(static_cast<std::size_t>(2 * cols + 2) + extra, 0.0);
  w[static_cast<std::size_t>(2 * cols - 1)] = -10.0;  // Max height.
  w[static_cast<std::size_t>(2 * cols)] = -1.0;       // Holes.
  return w;
}

}  // namespace gpfd::rl
