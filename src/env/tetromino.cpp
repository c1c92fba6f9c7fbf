#include "gpfd/env/tetromino.hpp"

#include <algorithm>
#include <vector>

namespace gpfd::env {
namespace {

using Cells = std::array<std::array<int, 2>, 4>;

Orientation make(const Cells& cells) {
  Orientation o;
  o.cells = cells;
  o.bottom.fill(1 << 20);
  for (const auto& [x, y] : cells) {
    o.width = std::max(o.width, x + 1);
    o.height = std::max(o.height, y + 1);
    o.bottom[static_cast<std::size_t>(x)] = std::min(o.bottom[static_cast<std::size_t>(x)], y);
    o.rowMask[static_cast<std::size_t>(y)] |= 1u << x;
  }
  return o;
}

// Cells (x, y), y up; each orientation is the previous one turned by 90 degrees (normalised).
const std::array<std::vector<Orientation>, kPieceCount>& table() {
  static const std::array<std::vector<Orientation>, kPieceCount> all{
      std::vector<Orientation>{make({{{0, 0}, {1, 0}, {2, 0}, {3, 0}}}),  // I
                               make({{{0, 0}, {0, 1}, {0, 2}, {0, 3}}})},
      std::vector<Orientation>{make({{{0, 0}, {1, 0}, {0, 1}, {1, 1}}})},  // O
      std::vector<Orientation>{make({{{0, 0}, {1, 0}, {2, 0}, {1, 1}}}),   // T
                               make({{{1, 0}, {1, 1}, {1, 2}, {0, 1}}}),
                               make({{{1, 0}, {0, 1}, {1, 1}, {2, 1}}}),
                               make({{{0, 0}, {0, 1}, {0, 2}, {1, 1}}})},
      std::vector<Orientation>{make({{{0, 0}, {1, 0}, {1, 1}, {2, 1}}}),  // S
                               make({{{1, 0}, {1, 1}, {0, 1}, {0, 2}}})},
      std::vector<Orientation>{make({{{1, 0}, {2, 0}, {0, 1}, {1, 1}}}),  // Z
                               make({{{0, 0}, {0, 1}, {1, 1}, {1, 2}}})},
      std::vector<Orientation>{make({{{0, 0}, {1, 0}, {2, 0}, {2, 1}}}),  // L
                               make({{{0, 0}, {1, 0}, {0, 1}, {0, 2}}}),
                               make({{{0, 0}, {0, 1}, {1, 1}, {2, 1}}}),
                               make({{{1, 0}, {1, 1}, {1, 2}, {0, 2}}})},
      std::vector<Orientation>{make({{{0, 0}, {1, 0}, {2, 0}, {0, 1}}}),  // J
                               make({{{0, 0}, {0, 1}, {0, 2}, {1, 2}}}),
                               make({{{0, 1}, {1, 1}, {2, 1}, {2, 0}}}),
                               make({{{1, 0}, {1, 1}, {1, 2}, {0, 0}}})},
  };
  return all;
}

}  // namespace

std::span<const Orientation> orientationsOf(int piece) {
  return table()[static_cast<std::size_t>(piece)];
}

int placementCount(int piece, int cols) {
  int count = 0;
  for (const Orientation& o : orientationsOf(piece)) count += std::max(0, cols - o.width + 1);
  return count;
}

}  // namespace gpfd::env
