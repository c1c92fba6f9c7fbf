// expr: gpfd's own sine and cosine, the `sin` and `cos` of feature functions.
//
// libm's sin and cos are not the same everywhere (glibc picks an FMA or SSE2 variant by CPU, other
// libms round differently) and have no vector form that agrees with the scalar one. gpfd defines
// them by one fixed sequence of IEEE double operations, no fused multiply-add, so that the
// interpreter, the scalar JIT, the 4-lane AVX2 batch kernel and the exported C and NumPy code all
// give the same bits on every x86-64 machine:
//   1. |x| < 2^-27: sin x = x, cos x = 1 (also keeps sin(-0) = -0).
//   2. |x| <= kLargeArgument: k = round-to-nearest-even(x * 2/pi) by the 1.5 * 2^52 trick, then
//      x - k pi/2 as a double-double r + y (Cody & Waite 1980 reduction with pi/2 split in three:
//      33 + 33 + 53 bits, so k * P1 and k * P2 are exact for |k| < 2^20), then the minimax
//      polynomials of fdlibm's __kernel_sin / __kernel_cos (Sun Microsystems 1993; coefficients
//      below) on [-pi/4, pi/4], and the quadrant k mod 4 picks +-sin r or +-cos r.
//   3. |x| > kLargeArgument (and inf, NaN): the C library's sin / cos.
// Accuracy (tests/expr/trig_test.cpp, against long double): below 1 ulp on |x| <= kLargeArgument.
#pragma once

namespace gpfd::expr::trig {

inline constexpr double kTiny = 0x1p-27;
inline constexpr double kLargeArgument = 1.0e6;  // |k| <= 636,620 < 2^20.
inline constexpr double kRoundMagic = 0x1.8p52;  // 1.5 * 2^52: (v + M) - M rounds v to an integer.
inline constexpr double kTwoOverPi = 6.36619772367581382433e-01;
// pi/2 = P1 + P2 + P3 (fdlibm e_rem_pio2.c: pio2_1, pio2_2, pio2_2t).
inline constexpr double kPio2Part1 = 1.57079632673412561417e+00;
inline constexpr double kPio2Part2 = 6.07710050630396597660e-11;
inline constexpr double kPio2Part3 = 2.02226624879595063154e-21;
// sin r = r + r^3 (S1 + z S2 + ... + z^5 S6), z = r^2 (fdlibm k_sin.c).
inline constexpr double kS1 = -1.66666666666666324348e-01;
inline constexpr double kS2 = 8.33333333332248946124e-03;
inline constexpr double kS3 = -1.98412698298579493134e-04;
inline constexpr double kS4 = 2.75573137070700676789e-06;
inline constexpr double kS5 = -2.50507602534068634195e-08;
inline constexpr double kS6 = 1.58969099521155010221e-10;
// cos r = 1 - z/2 + z^2 (C1 + z C2 + ... + z^5 C6) (fdlibm k_cos.c).
inline constexpr double kC1 = 4.16666666666666019037e-02;
inline constexpr double kC2 = -1.38888888888741095749e-03;
inline constexpr double kC3 = 2.48015872894767294178e-05;
inline constexpr double kC4 = -2.75573143513906633035e-07;
inline constexpr double kC5 = 2.08757232129817482790e-09;
inline constexpr double kC6 = -1.13596475577881948265e-11;

double sin(double x);
double cos(double x);

// sin x and cos x from one argument reduction: the same bits as sin(x) and cos(x).
template <class T>
struct SinCos {
  T sin, cos;
};
SinCos<double> sinCos(double x);

}  // namespace gpfd::expr::trig
