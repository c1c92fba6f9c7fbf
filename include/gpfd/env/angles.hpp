// env: wrapping angles into [-pi, pi].
#pragma once

#include <cmath>
#include <numbers>

#include "gpfd/util/lanes.hpp"

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

// The same on four or eight lanes, bit for bit: one turn of the loop for every lane, and the scalar
// function for the rare lanes that need more (or are far out, inf or NaN).
template <lanes::LaneType L>
L wrapAngle(L x) {
  constexpr double lo = -std::numbers::pi, hi = std::numbers::pi, period = hi - lo;
  const L once = lanes::select(x > hi, x - period, lanes::select(x < lo, x + period, x));
  const lanes::MaskOf<L> rest = once > hi || once < lo || !(lanes::abs(x) <= 64 * period);
  if (!lanes::anyOf(rest)) return once;
  return lanes::patchLanes(rest, x, once, [](double v) { return wrapAngle(v); });
}

}  // namespace gpfd::env
