// env: what the twins of Gymnasium's tasks share beyond GymnasiumTwin: their common parameters,
// their registry entries, and libm's pow as NumPy and Python call it.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "gpfd/env/gymnasium_twin.hpp"
#include "gpfd/util/params.hpp"

namespace gpfd::env::twin {

using numpy_scalar::Kind;
using numpy_scalar::Num;
using numpy_scalar::Promotion;

// `max_episode_steps` (gymnasium.make's keyword: the TimeLimit) and `numpy` (whose promotion
// rules the Python being twinned follows: 2, NEP 50, or 1, the legacy rules) over the config's
// `settings` (TwinSettings).
template <typename Config>
void declareTwinSettings(ParamTable<Config>& table) {
  table
      .integer(
          "max_episode_steps", [](auto& c) -> auto& { return c.settings.maxEpisodeSteps; }, 0,
          1000000000, "gymnasium.make's time limit in steps (truncation); 0 = none")
      .choice(
          "numpy", [](auto& c) -> auto& { return c.settings.promotion; },
          std::vector<std::pair<std::string, Promotion>>{{"2", Promotion::Nep50},
                                                         {"1", Promotion::Legacy}},
          "the NumPy whose type promotion the twinned Python follows: 2 (NEP 50) or 1 (legacy); "
          "gpfd's Python sets the one installed");
}

// x ** y on a float64 or Python float, as NumPy's scalar power and CPython's float_pow compute it:
// libm's pow, called so that the compiler cannot fold pow(x, 2.0) into x * x.
inline double libmPow(double x, double y) {
  static double (*volatile const pow)(double, double) = &::pow;
  return pow(x, y);
}

// sin(x) and cos(x) as libm's sin and cos give them (glibc's sincos shares their code).
inline void libmSinCos(double x, double& sine, double& cosine) {
#ifdef __GLIBC__
  ::sincos(x, &sine, &cosine);
#else
  sine = std::sin(x);
  cosine = std::cos(x);
#endif
}

// The spacing of doubles (`mantissaBits` 52) or floats (23) above a normal positive value:
// 2^(its exponent - mantissaBits). Below a power of two the spacing is half that: the squares
// below fall back on libm where fl(x * x) is a power of two and not exact.
inline double spacingAt(double magnitude, int mantissaBits) {
  const auto exponent = std::bit_cast<std::uint64_t>(magnitude) & 0x7ff0000000000000ULL;
  return std::bit_cast<double>(exponent - (static_cast<std::uint64_t>(mantissaBits) << 52));
}
inline bool isPowerOfTwo(double magnitude) {
  return (std::bit_cast<std::uint64_t>(magnitude) & 0x000fffffffffffffULL) == 0;
}

// |log2 v| bounded from v's binary exponent e: at most |e| + 1.
inline double log2Bound(double magnitude) {
  const auto exponent = static_cast<int>((std::bit_cast<std::uint64_t>(magnitude) >> 52) & 0x7ff);
  return std::abs(exponent - 1023) + 1.0;
}

// x * x - fl(x * x), exact (Dekker's product by Veltkamp's split), for |x| in (2^-450, 2^500).
inline double squareError(double x, double product) {
  const double split = 134217729.0 * x;  // 2^27 + 1
  const double high = split - (split - x), low = x - high;
  return ((high * high - product) + 2.0 * high * low) + low * low;
}

// pow(x, 2.0) as libm gives it, without calling libm where that cannot matter. glibc's pow is
// exp(y log x) (its e_pow.c states the parts: log's relative error 1.5 * 2^-68 without FMA, exp's
// 0.511 ulp, so at most 0.011 ulp before its final rounding): it errs from the exact square by at
// most 0.011 + |ln x^2| * 1.5 * 2^-68 * 2^53 ulp before rounding, so where the exact square lies
// farther than that from the midpoint between fl(x * x) and its neighbour, pow rounds it to
// fl(x * x) too. Near a midpoint, and for tiny, huge or non-finite squares, libm is asked.
inline double libmSquare(double x) {
  const double product = x * x;
  const double magnitude = std::fabs(product);
  if (!(magnitude > 0x1p-900 && magnitude < 0x1p1000)) return libmPow(x, 2.0);
  const double beforeRounding = 0.0111 + log2Bound(magnitude) * 0.6932 * 1.5 * 0x1p-15;
  const double margin = 0.5 - beforeRounding - 0.001;
  const double error = std::fabs(squareError(x, product));
  const bool clear =
      error < margin * spacingAt(magnitude, 52) && (error == 0.0 || !isPowerOfTwo(magnitude));
  return clear ? product : libmPow(x, 2.0);
}

// x ** y on a float32 scalar (NumPy's npy_powf): libm's powf, likewise.
inline float libmPowf(float x, float y) {
  static float (*volatile const powf)(float, float) = &::powf;
  return powf(x, y);
}

// powf(x, 2.0f) likewise: x * x is exact in double. glibc's powf computes exp2(y log2 x) in double
// and rounds that to float once; its e_powf.c states the double's relative error as
// |y log2 x| * ln 2 * 1.83 * 2^-33 + 1.69 * 2^-34, so where the exact square lies farther than
// that from the midpoint between its float rounding and a neighbour, powf returns that rounding.
inline float libmSquaref(float x) {
  const double exact = static_cast<double>(x) * x;
  const float rounded = static_cast<float>(exact);
  const double magnitude = std::fabs(static_cast<double>(rounded));
  if (!(magnitude > 0x1p-100 && magnitude < 0x1p100)) return libmPowf(x, 2.0f);
  const double relative = log2Bound(magnitude) * 0.6932 * 1.83 * 0x1p-33 + 1.69 * 0x1p-34;
  const double margin = 0.5 - relative * 0x1p24 - 0.001;
  const double error = std::fabs(exact - static_cast<double>(rounded));
  const bool clear =
      error < margin * spacingAt(magnitude, 23) && (error == 0.0 || !isPowerOfTwo(magnitude));
  return clear ? rounded : libmPowf(x, 2.0f);
}

// `x ** y` on values of NumPy's types: the promoted type's pow.
inline Num power(const Num& x, const Num& y) {
  const Kind kind = numpy_scalar::resultKind(x, y);
  double value = 0.0;
  if (kind == Kind::Float32) {
    const float base = static_cast<float>(x.value), exponent = static_cast<float>(y.value);
    value = exponent == 2.0f ? libmSquaref(base) : libmPowf(base, exponent);
  } else {
    value = y.value == 2.0 ? libmSquare(x.value) : libmPow(x.value, y.value);
  }
  return {value, kind, x.isPython() ? y.promotion : x.promotion};
}

// A Python float literal and a NumPy float64 scalar under `promotion`.
inline Num py(double value, Promotion promotion) { return {value, Kind::PyFloat, promotion}; }
inline Num f64(double value, Promotion promotion) { return {value, Kind::Float64, promotion}; }

// Gymnasium's Discrete(choices) and a one-dimensional Box [low, high] named `name`.
inline ActionSpace discreteActions(int choices) {
  ActionSpace space;
  space.kind = ActionSpace::Kind::Discrete;
  space.choices = {choices};
  space.names = {"action"};
  return space;
}
inline ActionSpace boxAction(double low, double high, const std::string& name) {
  ActionSpace space;
  space.low = {low};
  space.high = {high};
  space.names = {name};
  return space;
}

// The registry entry of a twin of `id`, made from its parameter table.
template <typename Twin, typename Config>
EnvInfo twinInfo(const std::string& id, const std::string& description) {
  EnvInfo info{id, description, Config::table().specs(), [](const Params& params) {
                 return std::make_unique<Twin>(Config::table().read(params));
               }};
  return info;
}

}  // namespace gpfd::env::twin
