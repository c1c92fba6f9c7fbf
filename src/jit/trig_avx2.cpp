#include "gpfd/jit/trig_avx2.hpp"

#include "gpfd/expr/trig.hpp"

#if defined(__x86_64__)
#include <immintrin.h>

namespace gpfd::jit {
namespace {

using namespace expr::trig;

#define GPFD_AVX2 __attribute__((target("avx2")))

GPFD_AVX2 inline __m256d splat(double v) { return _mm256_set1_pd(v); }
GPFD_AVX2 inline __m256d mul(__m256d a, __m256d b) { return _mm256_mul_pd(a, b); }
GPFD_AVX2 inline __m256d add(__m256d a, __m256d b) { return _mm256_add_pd(a, b); }
GPFD_AVX2 inline __m256d sub(__m256d a, __m256d b) { return _mm256_sub_pd(a, b); }

// The steps of expr/trig.cpp, lane by lane, in the same order. offset: 0 for sin, 1 for cos.
GPFD_AVX2 void sinOrCos4(double* x, unsigned offset) {
  const __m256d v = _mm256_loadu_pd(x);
  const __m256d a = _mm256_and_pd(v, _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffff)));
  const __m256d large = _mm256_cmp_pd(a, splat(kLargeArgument), _CMP_NLE_UQ);  // Or NaN.
  const __m256d tiny = _mm256_cmp_pd(a, splat(kTiny), _CMP_LT_OQ);

  // Reduction: x - k pi/2 = r + y, quadrant = k mod 4.
  const __m256d shifted = add(mul(v, splat(kTwoOverPi)), splat(kRoundMagic));
  const __m256i quadrant =
      _mm256_and_si256(_mm256_add_epi64(_mm256_castpd_si256(shifted), _mm256_set1_epi64x(offset)),
                       _mm256_set1_epi64x(3));
  const __m256d k = add(sub(shifted, splat(kRoundMagic)), _mm256_setzero_pd());
  const __m256d r1 = sub(v, mul(k, splat(kPio2Part1)));
  const __m256d w = mul(k, splat(kPio2Part2));
  const __m256d r2 = sub(r1, w);
  const __m256d tail = sub(sub(sub(r1, r2), w), mul(k, splat(kPio2Part3)));
  const __m256d r = add(r2, tail);
  const __m256d y = add(sub(r2, r), tail);
  const __m256d z = mul(r, r);

  // sin kernel.
  const __m256d vs = mul(z, r);
  __m256d p = add(splat(kS5), mul(z, splat(kS6)));
  p = add(splat(kS4), mul(z, p));
  p = add(splat(kS3), mul(z, p));
  p = add(splat(kS2), mul(z, p));
  const __m256d sinR =
      sub(r, sub(sub(mul(z, sub(mul(splat(0.5), y), mul(vs, p))), y), mul(vs, splat(kS1))));

  // cos kernel.
  __m256d c = add(splat(kC5), mul(z, splat(kC6)));
  c = add(splat(kC4), mul(z, c));
  c = add(splat(kC3), mul(z, c));
  c = add(splat(kC2), mul(z, c));
  c = mul(z, add(splat(kC1), mul(z, c)));
  const __m256d hz = mul(splat(0.5), z);
  const __m256d one = splat(1.0);
  const __m256d cw = sub(one, hz);
  const __m256d cosR = add(cw, add(sub(sub(one, cw), hz), sub(mul(z, c), mul(r, y))));

  // Quadrant: odd ones take cos r, 2 and 3 negate.
  const __m256i q1 = _mm256_and_si256(quadrant, _mm256_set1_epi64x(1));
  const __m256i q2 = _mm256_and_si256(quadrant, _mm256_set1_epi64x(2));
  const __m256d odd = _mm256_castsi256_pd(_mm256_cmpeq_epi64(q1, _mm256_set1_epi64x(1)));
  const __m256d negate = _mm256_castsi256_pd(_mm256_cmpeq_epi64(q2, _mm256_set1_epi64x(2)));
  __m256d result = _mm256_blendv_pd(sinR, cosR, odd);
  result = _mm256_xor_pd(result, _mm256_and_pd(negate, splat(-0.0)));
  result = _mm256_blendv_pd(result, offset == 0 ? v : one, tiny);

  // Large arguments (rare) take the scalar path, which calls the C library.
  const int largeLanes = _mm256_movemask_pd(large);
  double input[4];
  if (largeLanes != 0) _mm256_storeu_pd(input, v);
  _mm256_storeu_pd(x, result);
  for (int j = 0; largeLanes != 0 && j < 4; ++j) {
    if (largeLanes & (1 << j))
      x[j] = offset == 0 ? expr::trig::sin(input[j]) : expr::trig::cos(input[j]);
  }
}

}  // namespace

void sin4Avx2(double* x) { sinOrCos4(x, 0); }
void cos4Avx2(double* x) { sinOrCos4(x, 1); }

}  // namespace gpfd::jit
#endif
