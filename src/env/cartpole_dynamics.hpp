// env: cart-pole's dynamics written once over the number type T (double for CartPole, Lanes4 for
// four lanes of the batched cart-pole), so that every lane gives CartPole's bits.
#pragma once

#include <array>

#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/integrate.hpp"
#include "gpfd/expr/trig_lanes.hpp"

namespace gpfd::env::cartpole {

// Constants of Gymnasium CartPole-v1 (docs/benchmarks.md).
inline constexpr double kMassCart = 1.0, kMassPole = 0.1, kTotalMass = kMassCart + kMassPole;
inline constexpr double kHalfLength = 0.5, kPoleMassLength = kMassPole * kHalfLength;
inline constexpr double kXThreshold = 2.4;
inline constexpr double kThetaThreshold = 12 * 2 * 3.141592653589793 / 360;  // 0.2094395102393195

// d/dt (x, dx, th, dth) under `force`, in the operation order of Gymnasium's cartpole.py.
template <class T>
std::array<T, 4> derivative(double gravity, const std::array<T, 4>& s, T force) {
  const T dx = s[1], th = s[2], dth = s[3];
  const auto [sinTh, cosTh] = expr::trig::sinCos(th);
  const T temp = (force + kPoleMassLength * (dth * dth) * sinTh) / kTotalMass;
  const T ddth = (gravity * sinTh - cosTh * temp) /
                 (kHalfLength * (4.0 / 3.0 - kMassPole * (cosTh * cosTh) / kTotalMass));
  const T ddx = temp - kPoleMassLength * ddth * cosTh / kTotalMass;
  return {dx, ddx, dth, ddth};
}

// The force an action component stands for (a valid discrete index, or any continuous value:
// NaN -> 0, clipped to the bound).
template <class T>
T force(const CartPoleConfig& config, T action) {
  if (config.discrete) return lanes::select(action == 1.0, T(config.maxForce), T(-config.maxForce));
  return lanes::select(lanes::isNan(action), T(0.0),
                       lanes::clamp(action, -config.maxForce, config.maxForce));
}

// One control interval: `substeps` integration steps with the force held.
template <class T>
void advance(const CartPoleConfig& config, std::array<T, 4>& s, T force) {
  const double h = config.dt / config.substeps;
  const auto f = [&](const std::array<T, 4>& y) { return derivative(config.gravity, y, force); };
  for (int i = 0; i < config.substeps; ++i) s = integrateStep<4>(config.integrator, s, h, f);
}

// |x| > 2.4 or |th| > 12 degrees (bool, or a lane mask).
template <class T>
auto terminal(const std::array<T, 4>& s) {
  return s[0] < -kXThreshold || s[0] > kXThreshold || s[2] < -kThetaThreshold ||
         s[2] > kThetaThreshold;
}

}  // namespace gpfd::env::cartpole
