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

// The unit in the last place of a normal positive value with `mantissaBits` stored bits (52 for
// a double, 23 for a float): 2^(its exponent - mantissaBits), from the exponent's bits.
inline double ulpOf(double magnitude, int mantissaBits) {
  const auto exponent = std::bit_cast<std::uint64_t>(magnitude) & 0x7ff0000000000000ULL;
  return std::bit_cast<double>(exponent - (static_cast<std::uint64_t>(mantissaBits) << 52));
}

// pow(x, 2.0) as libm gives it, without calling libm where that cannot matter: glibc's pow errs
// by at most 0.54 ulp (the bound stated in its e_pow.c), so where the exact square lies within
// 0.45 ulp of the rounded product x * x (the product's error is exact by FMA), no other double is
// near enough and pow returns x * x. Near a rounding boundary, and for tiny, huge or non-finite
// squares, libm is asked.
inline double libmSquare(double x) {
  const double product = x * x;
  const double magnitude = std::fabs(product);
  if (!(magnitude > 0x1p-900 && magnitude < 0x1p1000)) return libmPow(x, 2.0);
  const double error = std::fma(x, x, -product);
  return std::fabs(error) < 0.45 * ulpOf(magnitude, 52) ? product : libmPow(x, 2.0);
}

// x ** y on a float32 scalar (NumPy's npy_powf): libm's powf, likewise.
inline float libmPowf(float x, float y) {
  static float (*volatile const powf)(float, float) = &::powf;
  return powf(x, y);
}

// powf(x, 2.0f) likewise: x * x is exact in double; glibc's powf errs by at most 0.82 ulp (its
// e_powf.c), so where the exact square lies within 0.15 ulp of its float rounding, powf returns
// that rounding.
inline float libmSquaref(float x) {
  const double exact = static_cast<double>(x) * x;
  const float rounded = static_cast<float>(exact);
  const float magnitude = std::fabs(rounded);
  if (!(magnitude > 0x1p-100f && magnitude < 0x1p100f)) return libmPowf(x, 2.0f);
  return std::fabs(exact - static_cast<double>(rounded)) < 0.15 * ulpOf(magnitude, 23)
             ? rounded
             : libmPowf(x, 2.0f);
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
