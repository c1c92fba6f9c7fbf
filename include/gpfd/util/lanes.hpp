// util: doubles side by side, for numerical code written once as a template over its number type:
// `double` for one lane, `Lanes4` for four, `Lanes8` for eight. Every lane operation is the IEEE
// operation of `double` lane by lane (no fused multiply-add: the project compiles with
// -ffp-contract=off), so a template gives in each lane the bits it gives with double.
//
// The lane types use the GCC/Clang vector extension, not intrinsics, so templates over them
// compile in any function. Inside a function marked GPFD_AVX2_KERNEL (target AVX2, everything
// inlined into it) Lanes4 operations become 256-bit AVX instructions; elsewhere SSE2 pairs. Such a
// function must only run where cpuHasAvx2() (util/cpu.hpp) is true. Lanes8 is meant for functions
// marked GPFD_AVX512_KERNEL (one 512-bit instruction per operation, 32 vector registers), which
// must only run where cpuHasAvx512(): eight lanes in one chain of operations hide its latency
// better than two groups of four one after the other.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__x86_64__)
#define GPFD_AVX2_KERNEL __attribute__((target("avx2"), flatten))
#define GPFD_AVX512_KERNEL __attribute__((target("avx2,avx512f,avx512dq,avx512vl"), flatten))
#else
#define GPFD_AVX2_KERNEL __attribute__((flatten))
#define GPFD_AVX512_KERNEL __attribute__((flatten))
#endif

namespace gpfd::lanes {

using RawLanes = double __attribute__((vector_size(32)));
using RawMask = std::int64_t __attribute__((vector_size(32)));
using RawLanes8 = double __attribute__((vector_size(64)));
using RawMask8 = std::int64_t __attribute__((vector_size(64)));

// The types are laid out with the instruction set they are used with: GCC fixes a struct's
// machine mode when it lays it out, and a struct laid out for SSE2 only would be copied in 16-byte
// pieces inside AVX code (store-forwarding stalls on every copy).
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
#pragma GCC target("avx2,avx512f,avx512dq,avx512vl")
#endif

struct Mask8 {
  RawMask8 bits;
};

struct Lanes8 {
  RawLanes8 v;

  Lanes8() = default;
  Lanes8(double x) : v{x, x, x, x, x, x, x, x} {}  // NOLINT(google-explicit-constructor)
  explicit Lanes8(RawLanes8 raw) : v(raw) {}
};

#ifdef GPFD_LANES_POP_OPTIONS
#pragma GCC pop_options
#undef GPFD_LANES_POP_OPTIONS
#endif

// Lanes per value of T: 1 for double, 4 for Lanes4, 8 for Lanes8.
template <class T>
inline constexpr std::size_t kWidth = sizeof(T) / sizeof(double);

template <class T>
concept LaneType = std::is_same_v<T, Lanes4> || std::is_same_v<T, Lanes8>;
template <class T>
concept MaskType = std::is_same_v<T, Mask4> || std::is_same_v<T, Mask8>;

// The mask type of T: bool for double, Mask4 for Lanes4, Mask8 for Lanes8.
template <class T>
struct MaskOfT {
  using type = bool;
};
template <>
struct MaskOfT<Lanes4> {
  using type = Mask4;
};
template <>
struct MaskOfT<Lanes8> {
  using type = Mask8;
};
template <class T>
using MaskOf = typename MaskOfT<T>::type;

// The lanes of T at p: one double, or kWidth<T> consecutive ones.
template <class T>
T loadAs(const double* p) {
  if constexpr (sizeof(T) == sizeof(double)) {
    return *p;
  } else {
    decltype(T{}.v) v;
    std::memcpy(&v, p, sizeof v);
    return T(v);
  }
}
inline Lanes4 load(const double* p) { return loadAs<Lanes4>(p); }
template <LaneType L>
void store(double* p, L x) {
  std::memcpy(p, &x.v, sizeof x.v);
}
inline void store(double* p, double x) { *p = x; }

// The arithmetic and comparisons of lane type L with mask type M, as plain functions (not
// templates) so that a double operand is broadcast implicitly.
#define GPFD_LANES_OPERATORS(L, M)                            \
  inline L operator+(L a, L b) { return L(a.v + b.v); }       \
  inline L operator-(L a, L b) { return L(a.v - b.v); }       \
  inline L operator*(L a, L b) { return L(a.v * b.v); }       \
  inline L operator/(L a, L b) { return L(a.v / b.v); }       \
  inline L operator-(L a) { return L(-a.v); }                 \
  inline L& operator+=(L& a, L b) { return a = a + b; }       \
  inline L& operator-=(L& a, L b) { return a = a - b; }       \
  inline L& operator*=(L& a, L b) { return a = a * b; }       \
  inline M operator<(L a, L b) { return {a.v < b.v}; }        \
  inline M operator>(L a, L b) { return {a.v > b.v}; }        \
  inline M operator<=(L a, L b) { return {a.v <= b.v}; }      \
  inline M operator>=(L a, L b) { return {a.v >= b.v}; }      \
  inline M operator==(L a, L b) { return {a.v == b.v}; }      \
  inline M operator||(M a, M b) { return {a.bits | b.bits}; } \
  inline M operator&&(M a, M b) { return {a.bits & b.bits}; } \
  inline M operator!(M a) { return {~a.bits}; }

GPFD_LANES_OPERATORS(Lanes4, Mask4)
GPFD_LANES_OPERATORS(Lanes8, Mask8)
#undef GPFD_LANES_OPERATORS

// The bits of each lane as an integer.
template <LaneType L>
auto bitsOf(L a) {
  return (decltype(MaskOf<L>{}.bits))a.v;
}
// Per lane: mask ? a : b.
template <LaneType L>
L select(MaskOf<L> mask, L a, L b) {
  return L((decltype(a.v))((bitsOf(a) & mask.bits) | (bitsOf(b) & ~mask.bits)));
}
template <LaneType L>
MaskOf<L> isNan(L a) {
  return {a.v != a.v};
}
// |a|: the sign bit cleared, as std::fabs does.
template <LaneType L>
L abs(L a) {
  return L((decltype(a.v))(bitsOf(a) & INT64_MAX));
}
// Bit j set when lane j of the mask is true.
template <MaskType M>
unsigned bitsOf(M m) {
  unsigned bits = 0;
  for (std::size_t j = 0; j < sizeof m.bits / sizeof m.bits[0]; ++j) {
    bits |= (m.bits[j] != 0 ? 1u : 0u) << j;
  }
  return bits;
}
template <MaskType M>
bool anyOf(M m) {
  return bitsOf(m) != 0;
}
// `value` with f(x) in the lanes where `which` is true. For rare lanes: it goes through memory
// (indexing a lane by a variable would keep the values in memory everywhere).
template <LaneType L, class F>
L patchLanes(MaskOf<L> which, L x, L value, F&& f) {
  const unsigned lanes = bitsOf(which);
  double in[kWidth<L>], out[kWidth<L>];
  store(in, x);
  store(out, value);
  for (std::size_t j = 0; j < kWidth<L>; ++j) {
    if (lanes & (1u << j)) out[j] = f(in[j]);
  }
  return loadAs<L>(out);
}
// std::clamp(a, lo, hi) lane by lane: a < lo ? lo : (hi < a ? hi : a) (NaN stays NaN).
template <LaneType L>
L clamp(L a, double lo, double hi) {
  return select(a < L(lo), L(lo), select(L(hi) < a, L(hi), a));
}

// The same operations on one double, so that templates read the same for both types.
inline double select(bool mask, double a, double b) { return mask ? a : b; }
inline bool anyOf(bool m) { return m; }
inline unsigned bitsOf(bool m) { return m ? 1u : 0u; }
inline bool isNan(double a) { return a != a; }
inline double abs(double a) { return std::fabs(a); }
inline double clamp(double a, double lo, double hi) { return a < lo ? lo : (hi < a ? hi : a); }

// A mask of T that is false in every lane.
template <class T>
MaskOf<T> noLane() {
  if constexpr (sizeof(T) == sizeof(double)) {
    return false;
  } else {
    return MaskOf<T>{};
  }
}

}  // namespace gpfd::lanes
