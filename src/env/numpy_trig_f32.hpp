// env: np.sin and np.cos of float32 values as NumPy computes them, for the twin of Acrobot-v1,
// whose reset observation takes them of its float32 start state. Where the CPU has fused
// multiply-add, NumPy 1.25-2.x use their own vectorised algorithm
// (numpy/_core/src/umath/loops_trigonometric.dispatch.cpp, "Vectorized approximate sine/cosine
// algorithms"): Cody-Waite reduction by pi/2 in three fused steps, then minimax polynomials on
// [-pi/4, pi/4] evaluated with fused multiply-adds, the quadrant choosing +-sin or +-cos; beyond
// |x| = 117435.992 (sine) or 71476.0625 (cosine), and on CPUs without FMA, the C library's.
// The constants below are NumPy's.
#pragma once

#include <cmath>

namespace gpfd::env::numpy_trig {

inline bool cpuHasFma() {
#if defined(__x86_64__) || defined(__i386__)
  static const bool has = __builtin_cpu_supports("fma");
  return has;
#else
  return false;  // Elsewhere NumPy's dispatch differs; gpfd claims the equality on x86-64.
#endif
}

inline float sinOrCos(float x, bool cosine) {
  if (std::isnan(x)) return x;
  const float limit = cosine ? 71476.0625f : 117435.992f;
  if (!cpuHasFma() || !(std::fabs(x) <= limit)) return cosine ? std::cos(x) : std::sin(x);
  const float magic = 0x1.800000p+23f;  // Adding and subtracting it rounds to an integer.
  const float quadrant = (x * 0x1.45f306p-1f + magic) - magic;
  float r = std::fma(quadrant, -0x1.921fb0p+00f, x);
  r = std::fma(quadrant, -0x1.5110b4p-22f, r);
  r = std::fma(quadrant, -0x1.846988p-48f, r);
  const float r2 = r * r;
  float c = std::fma(0x1.98e616p-16f, r2, -0x1.6c06dcp-10f);
  c = std::fma(c, r2, 0x1.55553cp-05f);
  c = std::fma(c, r2, -0x1.000000p-01f);
  c = std::fma(c, r2, 0x1.000000p+00f);
  float s = std::fma(0x1.7d3bbcp-19f, r2, -0x1.a06bbap-13f);
  s = std::fma(s, r2, 0x1.11119ap-07f);
  s = std::fma(s, r2, -0x1.555556p-03f);
  s = std::fma(s, r2, 0.0f);
  s = std::fma(s, r, r);
  const int k = static_cast<int>(quadrant) + (cosine ? 1 : 0);
  const float value = (k & 1) == 0 ? s : c;
  return (k & 2) == 2 ? 0.0f - value : value;
}

}  // namespace gpfd::env::numpy_trig
