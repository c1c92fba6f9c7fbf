// util: four doubles side by side, for numerical code written once as a template over its number
// type: `double` for one lane, `Lanes4` for four. Every Lanes4 operation is the IEEE operation of
// `double` lane by lane (no fused multiply-add: the project compiles with -ffp-contract=off, and
// the AVX2 target has no FMA), so a template gives in each lane the bits it gives with double.
//
// Lanes4 uses the GCC/Clang vector extension, not intrinsics, so templates over it compile in any
// function. Inside a function marked GPFD_AVX2_KERNEL (target AVX2, everything inlined into it)
// they become 256-bit AVX instructions; elsewhere SSE2 pairs. Such a function must only run where
// cpuHasAvx2() (util/cpu.hpp) is true.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__x86_64__)
#define GPFD_AVX2_KERNEL __attribute__((target("avx2"), flatten))
#else
#define GPFD_AVX2_KERNEL __attribute__((flatten))
#endif

namespace gpfd::lanes {

using RawLanes = double __attribute__((vector_size(32)));
using RawMask = std::int64_t __attribute__((vector_size(32)));

// The two types are laid out with AVX enabled: GCC fixes a struct's machine mode when it lays it
// out, and a struct laid out for SSE2 only would be copied in 16-byte pieces inside AVX2 code
// (store-forwarding stalls on every copy).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC target("avx2")
#define GPFD_LANES_POP_OPTIONS
#endif

// Per lane all ones (true) or all zeros (false), as comparisons give it.
struct Mask4 {
  RawMask bits;
};

struct Lanes4 {
  RawLanes v;

  Lanes4() = default;
  // Broadcast, implicit so that `0.5 * x` reads as it does for double.
  Lanes4(double x) : v{x, x, x, x} {}  // NOLINT(google-explicit-constructor)
  explicit Lanes4(RawLanes raw) : v(raw) {}
};

#ifdef GPFD_LANES_POP_OPTIONS
#pragma GCC pop_options
#undef GPFD_LANES_POP_OPTIONS
#endif

inline Lanes4 load(const double* p) {
  RawLanes v;
  std::memcpy(&v, p, sizeof v);
  return Lanes4(v);
}
inline void store(double* p, Lanes4 x) { std::memcpy(p, &x.v, sizeof x.v); }
inline void store(double* p, double x) { *p = x; }
// The lanes of T at p: one double, or four consecutive ones.
template <class T>
T loadAs(const double* p) {
  if constexpr (sizeof(T) == sizeof(double)) {
    return *p;
  } else {
    return load(p);
  }
}

inline Lanes4 operator+(Lanes4 a, Lanes4 b) { return Lanes4(a.v + b.v); }
inline Lanes4 operator-(Lanes4 a, Lanes4 b) { return Lanes4(a.v - b.v); }
inline Lanes4 operator*(Lanes4 a, Lanes4 b) { return Lanes4(a.v * b.v); }
inline Lanes4 operator/(Lanes4 a, Lanes4 b) { return Lanes4(a.v / b.v); }
inline Lanes4 operator-(Lanes4 a) { return Lanes4(-a.v); }
inline Lanes4& operator+=(Lanes4& a, Lanes4 b) { return a = a + b; }
inline Lanes4& operator-=(Lanes4& a, Lanes4 b) { return a = a - b; }
inline Lanes4& operator*=(Lanes4& a, Lanes4 b) { return a = a * b; }

inline Mask4 operator<(Lanes4 a, Lanes4 b) { return {a.v < b.v}; }
inline Mask4 operator>(Lanes4 a, Lanes4 b) { return {a.v > b.v}; }
inline Mask4 operator<=(Lanes4 a, Lanes4 b) { return {a.v <= b.v}; }
inline Mask4 operator>=(Lanes4 a, Lanes4 b) { return {a.v >= b.v}; }
inline Mask4 operator==(Lanes4 a, Lanes4 b) { return {a.v == b.v}; }
inline Mask4 operator||(Mask4 a, Mask4 b) { return {a.bits | b.bits}; }
inline Mask4 operator&&(Mask4 a, Mask4 b) { return {a.bits & b.bits}; }
inline Mask4 operator!(Mask4 a) { return {~a.bits}; }

// Per lane: mask ? a : b.
inline Lanes4 select(Mask4 mask, Lanes4 a, Lanes4 b) {
  return Lanes4((RawLanes)(((RawMask)a.v & mask.bits) | ((RawMask)b.v & ~mask.bits)));
}
inline bool anyOf(Mask4 m) { return (m.bits[0] | m.bits[1] | m.bits[2] | m.bits[3]) != 0; }
// Bit j set when lane j of the mask is true.
inline unsigned bitsOf(Mask4 m) {
  return (m.bits[0] != 0 ? 1u : 0u) | (m.bits[1] != 0 ? 2u : 0u) | (m.bits[2] != 0 ? 4u : 0u) |
         (m.bits[3] != 0 ? 8u : 0u);
}
// `value` with f(x) in the lanes where `which` is true. For rare lanes: it goes through memory
// (indexing a lane by a variable would keep the values in memory everywhere).
template <class F>
Lanes4 patchLanes(Mask4 which, Lanes4 x, Lanes4 value, F&& f) {
  const unsigned lanes = bitsOf(which);
  double in[4], out[4];
  store(in, x);
  store(out, value);
  for (int j = 0; j < 4; ++j) {
    if (lanes & (1u << j)) out[j] = f(in[j]);
  }
  return load(out);
}
inline Mask4 isNan(Lanes4 a) { return {a.v != a.v}; }
// |a|: the sign bit cleared, as std::fabs does.
inline Lanes4 abs(Lanes4 a) {
  return Lanes4((RawLanes)((RawMask)a.v & RawMask{INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX}));
}
// std::clamp(a, lo, hi) lane by lane: a < lo ? lo : (hi < a ? hi : a) (NaN stays NaN).
inline Lanes4 clamp(Lanes4 a, double lo, double hi) {
  return select(a < Lanes4(lo), Lanes4(lo), select(Lanes4(hi) < a, Lanes4(hi), a));
}
// The bits of each lane as an integer.
inline RawMask bitsOf(Lanes4 a) { return (RawMask)a.v; }

// Lanes per value of T: 1 for double, 4 for Lanes4.
template <class T>
inline constexpr std::size_t kWidth = sizeof(T) / sizeof(double);

// The same operations on one double, so that templates read the same for both types.
inline double select(bool mask, double a, double b) { return mask ? a : b; }
inline bool anyOf(bool m) { return m; }
inline unsigned bitsOf(bool m) { return m ? 1u : 0u; }
inline bool isNan(double a) { return a != a; }
inline double abs(double a) { return std::fabs(a); }
inline double clamp(double a, double lo, double hi) { return a < lo ? lo : (hi < a ? hi : a); }

// The mask type of T: bool for double, Mask4 for Lanes4.
template <class T>
struct MaskOfT {
  using type = bool;
};
template <>
struct MaskOfT<Lanes4> {
  using type = Mask4;
};
template <class T>
using MaskOf = typename MaskOfT<T>::type;

// A mask of T that is false in every lane.
template <class T>
MaskOf<T> noLane() {
  if constexpr (sizeof(T) == sizeof(double)) {
    return false;
  } else {
    return Mask4{RawMask{0, 0, 0, 0}};
  }
}

}  // namespace gpfd::lanes
