// env: the seven tetrominoes and their distinct orientations, as cell offsets.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace gpfd::env {

// Pieces in the order of the paper's "shape" state variable: I=0, O=1, T=2, S=3, Z=4, L=5, J=6.
inline constexpr int kPieceCount = 7;
inline constexpr std::array<char, kPieceCount> kPieceLetters{'I', 'O', 'T', 'S', 'Z', 'L', 'J'};
inline constexpr int kMaxOrientations = 4;  // The most orientations a piece has.

// One orientation: four cells (x to the right, y up) with min x = min y = 0. bottom[x] is the
// lowest y of the piece in column x (0 <= x < width), rowMask[y] the columns it fills in row y.
struct Orientation {
  int width = 0;
  int height = 0;
  std::array<std::array<int, 2>, 4> cells{};
  std::array<int, 4> bottom{};
  std::array<std::uint32_t, 4> rowMask{};
};

// The distinct orientations of a piece (I 2, O 1, T 4, S 2, Z 2, L 4, J 4). piece in [0, 7).
std::span<const Orientation> orientationsOf(int piece);

// Placements (orientation, leftmost column) of a piece on a board `cols` wide.
int placementCount(int piece, int cols);

}  // namespace gpfd::env
