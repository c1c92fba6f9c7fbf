// util: whether every value of a run of doubles is finite. One pass without an early exit: on
// short rows (feature rows, states) a branch per value costs more than reading them all, and
// Eigen's allFinite on a mapped row was measured slower on Tetris's 18-value rows
// (docs/performance.md, lambda-PI decisions).
#pragma once

#include <cmath>
#include <span>

namespace gpfd {

inline bool allFinite(std::span<const double> values) {
  bool finite = true;
  for (const double v : values) finite &= std::isfinite(v);
  return finite;
}

}  // namespace gpfd
