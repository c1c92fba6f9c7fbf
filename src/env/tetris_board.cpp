#include "gpfd/env/tetris_board.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdlib>

#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

// Set bits of a row, by the parallel-sum method (Hacker's Delight, section 5-1): std::popcount
// becomes a libgcc call where the target has no POPCNT instruction (baseline x86-64).
int cellCount(std::uint32_t v) {
  v = v - ((v >> 1) & 0x55555555u);
  v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
  v = (v + (v >> 4)) & 0x0f0f0f0fu;
  return static_cast<int>((v * 0x01010101u) >> 24);
}

}  // namespace

TetrisBoard::TetrisBoard(int rows, int cols)
    : rows_(rows), cols_(cols), full_(cols >= 32 ? ~0u : (1u << cols) - 1u) {
  if (rows < 4 || rows > kMaxRows || cols < 4 || cols > kMaxCols) {
    throw InputError(fmt::format("a Tetris board must have 4..{} rows and 4..{} columns, got {}x{}",
                                 kMaxRows, kMaxCols, rows, cols),
                     "tetris.rows/cols");
  }
}

void TetrisBoard::set(int row, int col, bool value) {
  auto& word = cells_[static_cast<std::size_t>(row)];
  word = value ? (word | (1u << col)) : (word & ~(1u << col));
}

void TetrisBoard::clear() { cells_.fill(0); }

int TetrisBoard::height(int col) const {
  for (int r = rows_ + 3; r >= 0; --r) {
    if (filled(r, col)) return r + 1;
  }
  return 0;
}

int TetrisBoard::holes() const {
  std::uint32_t seen = 0;
  int count = 0;
  for (int r = rows_ + 3; r >= 0; --r) {
    const std::uint32_t row = cells_[static_cast<std::size_t>(r)];
    count += cellCount(~row & seen & full_);
    seen |= row;
  }
  return count;
}

void TetrisBoard::heights(int* out) const {
  std::fill(out, out + cols_, 0);
  std::uint32_t seen = 0;
  for (int r = rows_ + 3; r >= 0 && seen != full_; --r) {
    std::uint32_t fresh = cells_[static_cast<std::size_t>(r)] & ~seen;
    seen |= fresh;
    while (fresh) {
      out[std::countr_zero(fresh)] = r + 1;
      fresh &= fresh - 1;
    }
  }
}

DropOutcome TetrisBoard::drop(int piece, int orientation, int column) {
  std::array<int, kMaxCols> columnHeights{};
  heights(columnHeights.data());
  return drop(piece, orientation, column, columnHeights.data());
}

DropOutcome TetrisBoard::drop(int piece, int orientation, int column, const int* columnHeights) {
  const Orientation& o = orientationsOf(piece)[static_cast<std::size_t>(orientation)];
  // Lowest collision-free position without sliding: the piece rests on the highest of its columns.
  int base = 0;
  for (int x = 0; x < o.width; ++x) {
    base = std::max(base, columnHeights[column + x] - o.bottom[static_cast<std::size_t>(x)]);
  }
  for (int y = 0; y < o.height; ++y) {
    cells_[static_cast<std::size_t>(base + y)] |= o.rowMask[static_cast<std::size_t>(y)] << column;
  }
  // Remove the full rows among those the piece touched, from the top down (only up to the hidden
  // rows: a piece can land higher only on a board set up with filled hidden rows, and the game is
  // over then).
  DropOutcome outcome;
  for (int r = std::min(base + o.height, rows_ + 4) - 1; r >= base; --r) {
    if (cells_[static_cast<std::size_t>(r)] == full_) {
      std::copy(cells_.begin() + r + 1, cells_.begin() + rows_ + 4, cells_.begin() + r);
      cells_[static_cast<std::size_t>(rows_ + 3)] = 0;
      ++outcome.rowsRemoved;
    }
  }
  for (int r = rows_; r < rows_ + 4; ++r) {
    if (cells_[static_cast<std::size_t>(r)] != 0) outcome.gameOver = true;
  }
  return outcome;
}

void TetrisBoard::features(TetrisFeatures kind, int piece, double* out) const {
  // One pass from the top: the first filled cell met in a column gives its height; every empty
  // cell below a filled one is a hole.
  std::array<int, kMaxCols> heights{};
  std::uint32_t seen = 0;
  int holeCount = 0;
  for (int r = rows_ + 3; r >= 0; --r) {
    const std::uint32_t row = cells_[static_cast<std::size_t>(r)];
    holeCount += cellCount(~row & seen & full_);
    std::uint32_t fresh = row & ~seen;
    while (fresh) {
      heights[static_cast<std::size_t>(std::countr_zero(fresh))] = r + 1;
      fresh &= fresh - 1;
    }
    seen |= row;
  }
  int maxHeight = 0;
  for (int c = 0; c < cols_; ++c) {
    out[c] = heights[static_cast<std::size_t>(c)];
    maxHeight = std::max(maxHeight, heights[static_cast<std::size_t>(c)]);
  }
  for (int c = 0; c + 1 < cols_; ++c) {
    out[cols_ + c] =
        std::abs(heights[static_cast<std::size_t>(c)] - heights[static_cast<std::size_t>(c + 1)]);
  }
  out[2 * cols_ - 1] = maxHeight;
  out[2 * cols_] = holeCount;
  out[2 * cols_ + 1] = kind == TetrisFeatures::Paper ? piece : 1.0;
}

std::vector<std::string> TetrisBoard::toText() const {
  std::vector<std::string> lines;
  for (int r = rows_ - 1; r >= 0; --r) {
    std::string line;
    for (int c = 0; c < cols_; ++c) line += filled(r, c) ? '#' : '.';
    lines.push_back(line);
  }
  return lines;
}

TetrisBoard TetrisBoard::fromText(const std::vector<std::string>& rowsTopDown) {
  const int rows = static_cast<int>(rowsTopDown.size());
  const int cols = rows > 0 ? static_cast<int>(rowsTopDown.front().size()) : 0;
  TetrisBoard board(rows, cols);
  for (int i = 0; i < rows; ++i) {
    const std::string& line = rowsTopDown[static_cast<std::size_t>(i)];
    if (static_cast<int>(line.size()) != cols) {
      throw InputError("every board row must have the same width", fmt::format("row {}", i + 1));
    }
    for (int c = 0; c < cols; ++c) {
      if (line[static_cast<std::size_t>(c)] != '#' && line[static_cast<std::size_t>(c)] != '.') {
        throw InputError("board cells must be '#' or '.'", fmt::format("row {}", i + 1));
      }
      board.set(rows - 1 - i, c, line[static_cast<std::size_t>(c)] == '#');
    }
  }
  return board;
}

}  // namespace gpfd::env
