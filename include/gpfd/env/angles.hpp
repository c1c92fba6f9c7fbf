// env: wrapping angles into [-pi, pi].
#pragma once

#include <cmath>
#include <numbers>

namespace gpfd::env {

// Wraps x into [-pi, pi] by adding or subtracting 2 pi, as Gymnasium's wrap() does (so that
// results agree bit for bit for the usual |x| < a few pi). Far-out values are first reduced with
// fmod so that the loop is short; NaN and inf are returned unchanged.
inline double wrapAngle(double x) {
  constexpr double lo = -std::numbers::pi, hi = std::numbers::pi, period = hi - lo;
  if (!std::isfinite(x)) return x;
  if (std::fabs(x) > 64 * period) x = std::fmod(x, period);
  while (x > hi) x -= period;
  while (x < lo) x += period;
  return x;
}

}  // namespace gpfd::env
