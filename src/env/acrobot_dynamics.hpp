// env: Acrobot's dynamics written once over the number type T (double for Acrobot, Lanes4 for four
// lanes of the batched Acrobot), so that every lane gives Acrobot's bits.
#pragma once

#include <array>
#include <numbers>

#include "gpfd/env/acrobot.hpp"
#include "gpfd/env/angles.hpp"
#include "gpfd/env/integrate.hpp"
#include "gpfd/expr/trig_lanes.hpp"

namespace gpfd::env::acrobot {

// Constants of Gymnasium Acrobot-v1 (docs/benchmarks.md).
inline constexpr double kM1 = 1.0, kM2 = 1.0, kL1 = 1.0, kLc1 = 0.5, kLc2 = 0.5, kI1 = 1.0,
                        kI2 = 1.0;
inline constexpr double kG = 9.8;
inline constexpr double kPi = std::numbers::pi;
inline constexpr double kMaxVel1 = 4 * kPi, kMaxVel2 = 9 * kPi;

// d/dt (th1, th2, dth1, dth2) under torque `tau` (the equations of docs/benchmarks.md).
template <class T>
std::array<T, 4> derivative(AcrobotConfig::Dynamics dynamics, const std::array<T, 4>& s, T tau) {
  const T th1 = s[0], th2 = s[1], dth1 = s[2], dth2 = s[3];
  const auto [sin2, cos2] = expr::trig::sinCos(th2);
  const T d1 =
      kM1 * kLc1 * kLc1 + kM2 * (kL1 * kL1 + kLc2 * kLc2 + 2 * kL1 * kLc2 * cos2) + kI1 + kI2;
  const T d2 = kM2 * (kLc2 * kLc2 + kL1 * kLc2 * cos2) + kI2;
  const T phi2 = kM2 * kLc2 * kG * expr::trig::cos(th1 + th2 - kPi / 2.0);
  const T phi1 = -kM2 * kL1 * kLc2 * (dth2 * dth2) * sin2 -
                 2 * kM2 * kL1 * kLc2 * dth2 * dth1 * sin2 +
                 (kM1 * kLc1 + kM2 * kL1) * kG * expr::trig::cos(th1 - kPi / 2.0) + phi2;
  T numerator = tau + d2 / d1 * phi1;
  if (dynamics == AcrobotConfig::Dynamics::Book) {
    numerator -= kM2 * kL1 * kLc2 * (dth1 * dth1) * sin2;
  }
  numerator -= phi2;
  const T ddth2 = numerator / (kM2 * kLc2 * kLc2 + kI2 - d2 * d2 / d1);
  const T ddth1 = -(d2 * ddth2 + phi1) / d1;
  return {dth1, dth2, ddth1, ddth2};
}

// The torque an action component stands for (a valid discrete index, or any continuous value:
// NaN -> 0, clipped to the bound).
template <class T>
T torque(const AcrobotConfig& config, T action) {
  if (config.discrete) return (action - 1.0) * config.maxTorque;
  return lanes::select(lanes::isNan(action), T(0.0),
                       lanes::clamp(action, -config.maxTorque, config.maxTorque));
}

// One control interval: `substeps` integration steps with the torque held, the angles wrapped and
// the velocities clipped after each.
template <class T>
void advance(const AcrobotConfig& config, std::array<T, 4>& s, T tau) {
  const double h = config.dt / config.substeps;
  const auto f = [&](const std::array<T, 4>& y) { return derivative(config.dynamics, y, tau); };
  for (int i = 0; i < config.substeps; ++i) {
    s = integrateStep<4>(config.integrator, s, h, f);
    s[0] = wrapAngle(s[0]);
    s[1] = wrapAngle(s[1]);
    s[2] = lanes::clamp(s[2], -kMaxVel1, kMaxVel1);
    s[3] = lanes::clamp(s[3], -kMaxVel2, kMaxVel2);
  }
}

// The tip above the bar: -cos th1 - cos(th1 + th2) > 1 (bool, or a lane mask).
template <class T>
auto terminal(const std::array<T, 4>& s) {
  return -expr::trig::cos(s[0]) - expr::trig::cos(s[1] + s[0]) > 1.0;
}

}  // namespace gpfd::env::acrobot
