#include "gpfd/expr/trig.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

#include "gpfd/expr/trig_lanes.hpp"

namespace gpfd::expr::trig {
namespace {

// sin(x) for quadrant offset 0, cos(x) for offset 1: cos x = sin(x + pi/2).
double sinOrCos(double x, unsigned offset) {
  const double a = std::fabs(x);
  if (a < kTiny) return offset == 0 ? x : 1.0;
  if (!(a <= kLargeArgument)) return offset == 0 ? std::sin(x) : std::cos(x);
  const detail::Reduction<double> red = detail::reduce(x);
  const auto quadrant = static_cast<unsigned>(std::bit_cast<std::uint64_t>(red.shifted) & 3u);
  const unsigned q = (quadrant + offset) & 3u;
  const double v = (q & 1u) ? detail::cosKernel(red.r, red.y) : detail::sinKernel(red.r, red.y);
  return (q & 2u) ? -v : v;
}

}  // namespace

double sin(double x) { return sinOrCos(x, 0); }
double cos(double x) { return sinOrCos(x, 1); }

SinCos<double> sinCos(double x) {
  const double a = std::fabs(x);
  if (a < kTiny) return {x, 1.0};
  if (!(a <= kLargeArgument)) return {std::sin(x), std::cos(x)};
  const detail::Reduction<double> red = detail::reduce(x);
  const auto q = static_cast<unsigned>(std::bit_cast<std::uint64_t>(red.shifted) & 3u);
  const double s = detail::sinKernel(red.r, red.y), c = detail::cosKernel(red.r, red.y);
  const double sinAbs = (q & 1u) ? c : s, cosAbs = (q & 1u) ? s : c;
  return {(q & 2u) ? -sinAbs : sinAbs, ((q + 1u) & 2u) ? -cosAbs : cosAbs};
}

}  // namespace gpfd::expr::trig
