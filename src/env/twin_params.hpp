// env: what the twins of Gymnasium's tasks share beyond GymnasiumTwin: their common parameters,
// their registry entries, and libm's pow as NumPy and Python call it.
#pragma once

#include <cmath>
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

// x ** y on a float32 scalar (NumPy's npy_powf): libm's powf, likewise.
inline float libmPowf(float x, float y) {
  static float (*volatile const powf)(float, float) = &::powf;
  return powf(x, y);
}

// `x ** y` on values of NumPy's types: the promoted type's pow.
inline Num power(const Num& x, const Num& y) {
  const Kind kind = numpy_scalar::resultKind(x, y);
  const double value =
      kind == Kind::Float32
          ? static_cast<double>(libmPowf(static_cast<float>(x.value), static_cast<float>(y.value)))
          : libmPow(x.value, y.value);
  return {value, kind, x.isPython() ? y.promotion : x.promotion};
}

// A Python float literal and a NumPy float64 scalar under `promotion`.
inline Num py(double value, Promotion promotion) { return {value, Kind::PyFloat, promotion}; }
inline Num f64(double value, Promotion promotion) { return {value, Kind::Float64, promotion}; }

// The registry entry of a twin of `id`, made from its parameter table.
template <typename Twin, typename Config>
EnvInfo twinInfo(const std::string& id, const std::string& description) {
  EnvInfo info{id, description, Config::table().specs(), [](const Params& params) {
                 return std::make_unique<Twin>(Config::table().read(params));
               }};
  return info;
}

}  // namespace gpfd::env::twin
