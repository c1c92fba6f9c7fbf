// env: Tetris afterstates in bulk. The column heights and the hole count of the current board are
// computed once; a placement that removes no row changes only the columns the piece covers: each
// rises to the piece's top there, and the empty cells between the old height and the piece's
// lowest cell there become holes (a tetromino's cells are contiguous in every column). A placement
// that removes rows, or a board with cells above the visible rows, takes the reference path (a
// drop on a copy of the board and a full scan), so the values are always the reference's.
#include <algorithm>
#include <array>
#include <cstdlib>

#include "gpfd/env/tetris.hpp"

namespace gpfd::env {
namespace {

// The highest cell of each column of an orientation.
std::array<int, 4> columnTops(const Orientation& o) {
  std::array<int, 4> top{};
  for (int x = 0; x < o.width; ++x) {
    for (int y = 0; y < o.height; ++y) {
      if ((o.rowMask[static_cast<std::size_t>(y)] >> x) & 1u) top[static_cast<std::size_t>(x)] = y;
    }
  }
  return top;
}

}  // namespace

void Tetris::afterstates(TetrisAfterstates& out) const {
  const int rows = config_.rows, cols = config_.cols;
  for (int r = rows; r < rows + 4; ++r) {
    if (board_.rowBits(r) != 0) return afterstatesReference(out);
  }
  const int count = placementCount(piece_, cols);
  const std::size_t dim = state_.size();
  out.featureDim = dim;
  out.placements.resize(static_cast<std::size_t>(count));
  out.features.resize(static_cast<std::size_t>(count) * dim);
  std::array<int, TetrisBoard::kMaxCols> heights{}, after{};
  board_.heights(heights.data());
  const int holes = board_.holes();
  const int maxHeight = *std::max_element(heights.begin(), heights.begin() + cols);
  const double last = config_.state == TetrisFeatures::Paper ? piece_ : 1.0;
  const auto orientations = orientationsOf(piece_);
  std::size_t i = 0;
  for (std::size_t o = 0; o < orientations.size(); ++o) {
    const Orientation& shape = orientations[o];
    const std::array<int, 4> top = columnTops(shape);
    const int columns = cols - shape.width + 1;
    for (int c = 0; c < columns; ++c, ++i) {
      double* f = out.features.data() + i * dim;
      int base = 0;
      for (int x = 0; x < shape.width; ++x) {
        base = std::max(base, heights[static_cast<std::size_t>(c + x)] -
                                  shape.bottom[static_cast<std::size_t>(x)]);
      }
      bool removes = false;
      for (int y = 0; y < shape.height && !removes; ++y) {
        const std::uint32_t row =
            board_.rowBits(base + y) | (shape.rowMask[static_cast<std::size_t>(y)] << c);
        removes = row == board_.fullRow();
      }
      if (removes) {
        TetrisBoard board = board_;
        const DropOutcome outcome = board.drop(piece_, static_cast<int>(o), c, heights.data());
        out.placements[i] = {static_cast<int>(o), c, outcome.rowsRemoved, outcome.gameOver};
        board.features(config_.state, piece_, f);
        continue;
      }
      std::copy(heights.begin(), heights.begin() + cols, after.begin());
      int newHoles = holes, newMax = maxHeight;
      for (int x = 0; x < shape.width; ++x) {
        const auto column = static_cast<std::size_t>(c + x);
        newHoles += base + shape.bottom[static_cast<std::size_t>(x)] - heights[column];
        after[column] = base + top[static_cast<std::size_t>(x)] + 1;
        newMax = std::max(newMax, after[column]);
      }
      out.placements[i] = {static_cast<int>(o), c, 0, base + shape.height > rows};
      for (int k = 0; k < cols; ++k) f[k] = after[static_cast<std::size_t>(k)];
      for (int k = 0; k + 1 < cols; ++k) {
        f[cols + k] =
            std::abs(after[static_cast<std::size_t>(k)] - after[static_cast<std::size_t>(k + 1)]);
      }
      f[2 * cols - 1] = newMax;
      f[2 * cols] = newHoles;
      f[2 * cols + 1] = last;
    }
  }
}

}  // namespace gpfd::env
