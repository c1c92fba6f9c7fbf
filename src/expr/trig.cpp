#include "gpfd/expr/trig.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

namespace gpfd::expr::trig {
namespace {

// x - k pi/2 = r + y (double-double), and k mod 4, for |x| <= kLargeArgument. The AVX2 version
// (src/jit/trig_avx2.cpp) performs the same operations in the same order.
struct Reduced {
  double r, y;
  unsigned quadrant;
};

Reduced reduce(double x) {
  const double shifted = x * kTwoOverPi + kRoundMagic;
  const unsigned quadrant = static_cast<unsigned>(std::bit_cast<std::uint64_t>(shifted) & 3u);
  const double k = (shifted - kRoundMagic) + 0.0;  // + 0 turns k = -0 into +0.
  const double r1 = x - k * kPio2Part1;            // Exact (Sterbenz; k * P1 is exact).
  const double w = k * kPio2Part2;                 // Exact.
  const double r2 = r1 - w;
  const double tail = ((r1 - r2) - w) - k * kPio2Part3;
  const double r = r2 + tail;
  return {r, (r2 - r) + tail, quadrant};
}

// sin(r + y), cos(r + y) for |r| <= pi/4 (fdlibm's kernel forms).
double sinKernel(double r, double y) {
  const double z = r * r;
  const double v = z * r;
  const double p = kS2 + z * (kS3 + z * (kS4 + z * (kS5 + z * kS6)));
  return r - ((z * (0.5 * y - v * p) - y) - v * kS1);
}

double cosKernel(double r, double y) {
  const double z = r * r;
  const double p = z * (kC1 + z * (kC2 + z * (kC3 + z * (kC4 + z * (kC5 + z * kC6)))));
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  return w + (((1.0 - w) - hz) + (z * p - r * y));
}

// sin(x) for quadrant offset 0, cos(x) for offset 1: cos x = sin(x + pi/2).
double sinOrCos(double x, unsigned offset) {
  const double a = std::fabs(x);
  if (a < kTiny) return offset == 0 ? x : 1.0;
  if (!(a <= kLargeArgument)) return offset == 0 ? std::sin(x) : std::cos(x);
  const Reduced red = reduce(x);
  const unsigned q = (red.quadrant + offset) & 3u;
  const double v = (q & 1u) ? cosKernel(red.r, red.y) : sinKernel(red.r, red.y);
  return (q & 2u) ? -v : v;
}

}  // namespace

double sin(double x) { return sinOrCos(x, 0); }
double cos(double x) { return sinOrCos(x, 1); }

}  // namespace gpfd::expr::trig
