// env: NumPy's scalar arithmetic, so that a twin of a Gymnasium environment computes what its
// Python computes, rounding for rounding. A value carries its type: a Python int or float, or a
// NumPy float32 or float64 scalar; an operation's result type follows NumPy's promotion rules:
// NEP 50 (NumPy 2: a Python number takes the NumPy operand's type, so float32 * 0.0015 is a
// float32 product of float32(0.0015)) or the legacy rules of NumPy 1.x (an operation of scalars
// alone promotes a Python float as float64 and a Python int as int64, so float32 * 0.0015 and
// float32 * 3 are float64). Comparisons promote alike. Only what the twins use is here: + - * /,
// comparisons, libm's functions on doubles, Python's min and max, np.clip.
#pragma once

#include <cmath>
#include <cstdint>

#define GPFD_NUMPY_INLINE [[gnu::always_inline]] inline

namespace gpfd::env::numpy_scalar {

enum class Promotion : std::uint8_t { Nep50, Legacy };

// x rounded to float32 (NumPy's astype(np.float32)), the float held where the compiler cannot
// see through it (an empty asm on an SSE register on x86-64, a volatile elsewhere): GCC 12.2's SLP
// vectoriser (-O2 and -O3) drops a pair of static_cast<float> results stored side by side into
// doubles, storing them unrounded (seen in MountainCarContinuous-v0's state and Acrobot-v1's and
// Pendulum-v1's observations; two adjacent `out[i] = static_cast<float>(x)` stores reproduce it,
// and -fno-tree-slp-vectorize makes it go). Where a float32 rounding matters, use this.
inline double toFloat32(double x) {
#if defined(__GNUC__) && defined(__x86_64__)
  float rounded = static_cast<float>(x);
  asm("" : "+x"(rounded));  // The register holds the float: the rounding stays.
  return rounded;
#else
  volatile float rounded = static_cast<float>(x);
  return rounded;
#endif
}
enum class Kind : std::uint8_t { PyInt, PyFloat, Float32, Float64 };

struct Num {
  double value = 0.0;
  Kind kind = Kind::PyFloat;
  Promotion promotion = Promotion::Nep50;

  GPFD_NUMPY_INLINE bool isPython() const { return kind == Kind::PyInt || kind == Kind::PyFloat; }
};

// The type of `a op b` (op arithmetic or a comparison).
GPFD_NUMPY_INLINE Kind resultKind(const Num& a, const Num& b) {
  if (a.isPython() && b.isPython()) {
    return a.kind == Kind::PyFloat || b.kind == Kind::PyFloat ? Kind::PyFloat : Kind::PyInt;
  }
  if (a.promotion == Promotion::Nep50) {
    if (a.isPython()) return b.kind;  // A weak Python number takes the NumPy type.
    if (b.isPython()) return a.kind;
    return a.kind == Kind::Float32 && b.kind == Kind::Float32 ? Kind::Float32 : Kind::Float64;
  }
  // Legacy: scalars alone promote by type; a Python float is a float64, a Python int an int64,
  // and float32 with int64 is float64.
  return a.kind == Kind::Float32 && b.kind == Kind::Float32 ? Kind::Float32 : Kind::Float64;
}

template <class Op>
GPFD_NUMPY_INLINE Num apply(const Num& a, const Num& b, Op op) {
  const Kind kind = resultKind(a, b);
  const double value =
      kind == Kind::Float32
          ? static_cast<double>(op(static_cast<float>(a.value), static_cast<float>(b.value)))
          : op(a.value, b.value);
  return {value, kind, a.isPython() ? b.promotion : a.promotion};
}

template <class Op>
GPFD_NUMPY_INLINE bool compare(const Num& a, const Num& b, Op op) {
  if (resultKind(a, b) == Kind::Float32) {
    return op(static_cast<float>(a.value), static_cast<float>(b.value));
  }
  return op(a.value, b.value);
}

GPFD_NUMPY_INLINE Num operator+(const Num& a, const Num& b) {
  return apply(a, b, [](auto x, auto y) { return x + y; });
}
GPFD_NUMPY_INLINE Num operator-(const Num& a, const Num& b) {
  return apply(a, b, [](auto x, auto y) { return x - y; });
}
GPFD_NUMPY_INLINE Num operator*(const Num& a, const Num& b) {
  return apply(a, b, [](auto x, auto y) { return x * y; });
}
GPFD_NUMPY_INLINE Num operator/(const Num& a, const Num& b) {
  return apply(a, b, [](auto x, auto y) { return x / y; });
}
GPFD_NUMPY_INLINE Num operator-(const Num& a) { return {-a.value, a.kind, a.promotion}; }
GPFD_NUMPY_INLINE bool operator<(const Num& a, const Num& b) {
  return compare(a, b, [](auto x, auto y) { return x < y; });
}
GPFD_NUMPY_INLINE bool operator>(const Num& a, const Num& b) { return b < a; }
GPFD_NUMPY_INLINE bool operator<=(const Num& a, const Num& b) {
  return compare(a, b, [](auto x, auto y) { return x <= y; });
}
GPFD_NUMPY_INLINE bool operator>=(const Num& a, const Num& b) { return b <= a; }
GPFD_NUMPY_INLINE bool operator==(const Num& a, const Num& b) {
  return compare(a, b, [](auto x, auto y) { return x == y; });
}

// Python's max(a, b) and min(a, b): the first unless the second is strictly greater (smaller).
GPFD_NUMPY_INLINE Num pyMax(const Num& a, const Num& b) { return b > a ? b : a; }
GPFD_NUMPY_INLINE Num pyMin(const Num& a, const Num& b) { return b < a ? b : a; }

// np.clip(x, low, high) with Python bounds, of a float64 scalar or of an element of an array
// (whose type it keeps under both rules): NaN stays NaN (NumPy's maximum and minimum).
GPFD_NUMPY_INLINE Num npClip(const Num& x, const Num& low, const Num& high) {
  Num out = x;
  out.kind = x.isPython() ? Kind::Float64 : x.kind;
  if (std::isnan(x.value)) return out;
  if (x < low) out.value = low.value;
  if (x > high) out.value = high.value;
  if (out.kind == Kind::Float32) out.value = static_cast<float>(out.value);
  return out;
}

}  // namespace gpfd::env::numpy_scalar
