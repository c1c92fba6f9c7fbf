// env: a Tetris board as one bit mask per row, with the drop rule and the board features of
// docs/benchmarks.md.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpfd/env/tetromino.hpp"

namespace gpfd::env {

enum class TetrisFeatures {
  Paper,      // c heights, c-1 |differences|, max height, holes, piece index (2c + 2 values).
  Bertsekas,  // c heights, c-1 |differences|, max height, holes, constant 1 (2c + 2 values).
};

// Number of values features() writes: 2 cols + 2 for both kinds.
inline int tetrisFeatureCount(int cols) { return 2 * cols + 2; }

struct DropOutcome {
  int rowsRemoved = 0;
  bool gameOver = false;  // After removal, some column exceeds the board height.
};

// rows x cols cells, row 0 at the bottom, with 4 hidden rows above the top for a piece that
// overflows. Limits: 4 <= rows <= kMaxRows, 4 <= cols <= kMaxCols.
class TetrisBoard {
 public:
  static constexpr int kMaxRows = 60;
  static constexpr int kMaxCols = 30;

  TetrisBoard(int rows, int cols);

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  bool filled(int row, int col) const {
    return (cells_[static_cast<std::size_t>(row)] >> col) & 1u;
  }
  // Row `row` (0 <= row < rows + 4) as a bit mask, bit c for column c; a full row is fullRow().
  std::uint32_t rowBits(int row) const { return cells_[static_cast<std::size_t>(row)]; }
  std::uint32_t fullRow() const { return full_; }
  // The rows that the board stores (rows + 8: the hidden ones too), for rowBits and setRowBits.
  int storedRows() const { return rows_ + 8; }
  void set(int row, int col, bool value);
  // Sets row `row` (0 <= row < storedRows()) to `bits`, which must lie within fullRow().
  void setRowBits(int row, std::uint32_t bits) { cells_[static_cast<std::size_t>(row)] = bits; }
  void clear();

  // Drops orientation `orientation` of `piece` with its leftmost cell in `column` (both already
  // valid): it falls straight down to the lowest free position, full rows are removed.
  DropOutcome drop(int piece, int orientation, int column);
  // The same with the column heights of this board given (cols values, from heights()).
  DropOutcome drop(int piece, int orientation, int column, const int* columnHeights);
  void heights(int* out) const;

  // Column height = index (1-based) of the highest filled cell, 0 when empty; a hole is an empty
  // cell below a filled one. Writes tetrisFeatureCount(cols) values; `piece` fills the last value
  // of the Paper kind.
  void features(TetrisFeatures kind, int piece, double* out) const;
  int height(int col) const;
  int holes() const;

  // Rows from the top down, '#' filled and '.' empty; fromText throws InputError on bad text.
  std::vector<std::string> toText() const;
  static TetrisBoard fromText(const std::vector<std::string>& rowsTopDown);

  bool operator==(const TetrisBoard& other) const = default;

 private:
  int rows_;
  int cols_;
  std::uint32_t full_;
  // 4 hidden rows, and 4 more: a piece dropped on a board whose hidden rows are already filled
  // (setBoard) lands above them.
  std::array<std::uint32_t, kMaxRows + 8> cells_{};
};

}  // namespace gpfd::env
