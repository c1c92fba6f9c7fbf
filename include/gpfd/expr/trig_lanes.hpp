// expr: gpfd's sine and cosine (trig.hpp) on four or eight lanes at once, bit-identical lane by
// lane to trig::sin and trig::cos: both are written once, below, as templates over the number type
// (util/lanes.hpp), and the lane version replaces the branches of the scalar one by selects.
// Lanes beyond kLargeArgument (and inf, NaN) call the scalar function, as it calls the C library.
#pragma once

#include "gpfd/expr/trig.hpp"
#include "gpfd/util/lanes.hpp"

namespace gpfd::expr::trig {
namespace detail {

// x - k pi/2 = r + y (double-double) for |x| <= kLargeArgument; `shifted` holds k in its low
// mantissa bits (the 1.5 * 2^52 trick), so k mod 4 = its bits & 3.
template <class T>
struct Reduction {
  T r, y, shifted;
};

template <class T>
Reduction<T> reduce(T x) {
  const T shifted = x * kTwoOverPi + kRoundMagic;
  const T k = (shifted - kRoundMagic) + 0.0;  // + 0 turns k = -0 into +0.
  const T r1 = x - k * kPio2Part1;            // Exact (Sterbenz; k * P1 is exact).
  const T w = k * kPio2Part2;                 // Exact.
  const T r2 = r1 - w;
  const T tail = ((r1 - r2) - w) - k * kPio2Part3;
  const T r = r2 + tail;
  return {r, (r2 - r) + tail, shifted};
}

// sin(r + y), cos(r + y) for |r| <= pi/4 (fdlibm's kernel forms).
template <class T>
T sinKernel(T r, T y) {
  const T z = r * r;
  const T v = z * r;
  const T p = kS2 + z * (kS3 + z * (kS4 + z * (kS5 + z * kS6)));
  return r - ((z * (0.5 * y - v * p) - y) - v * kS1);
}

template <class T>
T cosKernel(T r, T y) {
  const T z = r * r;
  const T p = z * (kC1 + z * (kC2 + z * (kC3 + z * (kC4 + z * (kC5 + z * kC6)))));
  const T hz = 0.5 * z;
  const T w = 1.0 - hz;
  return w + (((1.0 - w) - hz) + (z * p - r * y));
}

}  // namespace detail

// sin and cos of four (Lanes4) or eight (Lanes8) arguments from one reduction.
template <lanes::LaneType L>
SinCos<L> sinCos(L x) {
  using M = lanes::MaskOf<L>;
  const L a = lanes::abs(x);
  const M tiny = a < L(kTiny);
  const M large = !(a <= L(kLargeArgument));  // Or NaN.
  const detail::Reduction<L> red = detail::reduce(x);
  const L s = detail::sinKernel(red.r, red.y), c = detail::cosKernel(red.r, red.y);
  // Quadrant q = k mod 4: sin x = (q odd ? cos r : sin r), negated for q = 2, 3; cos x is sin of
  // quadrant q + 1.
  const auto q = lanes::bitsOf(red.shifted);
  const M odd{(q & 1) != 0};
  const L sinAbs = lanes::select(odd, c, s), cosAbs = lanes::select(odd, s, c);
  SinCos<L> out{lanes::select(M{(q & 2) != 0}, -sinAbs, sinAbs),
                lanes::select(M{((q + 1) & 2) != 0}, -cosAbs, cosAbs)};
  out.sin = lanes::select(tiny, x, out.sin);
  out.cos = lanes::select(tiny, L(1.0), out.cos);
  if (lanes::anyOf(large)) {
    out.sin = lanes::patchLanes(large, x, out.sin, [](double v) { return sin(v); });
    out.cos = lanes::patchLanes(large, x, out.cos, [](double v) { return cos(v); });
  }
  return out;
}

template <lanes::LaneType L>
L sin(L x) {
  return sinCos(x).sin;
}
template <lanes::LaneType L>
L cos(L x) {
  return sinCos(x).cos;
}

}  // namespace gpfd::expr::trig
