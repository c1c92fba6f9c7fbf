// env: one explicit integration step of an autonomous ODE dy/dt = f(y) over fixed-size states.
#pragma once

#include <array>
#include <cstddef>

namespace gpfd::env {

enum class Integrator { Euler, Rk4 };

template <std::size_t N>
using Vec = std::array<double, N>;

// The integrators are templates over the number type T: double, or util/lanes.hpp's Lanes4 for
// four states at once (the same operations lane by lane).

// Explicit Euler: y + h f(y).
template <std::size_t N, typename T, typename F>
std::array<T, N> eulerStep(const std::array<T, N>& y, double h, F&& f) {
  const std::array<T, N> k = f(y);
  std::array<T, N> out;
  for (std::size_t i = 0; i < N; ++i) out[i] = y[i] + h * k[i];
  return out;
}

// Classical fourth-order Runge-Kutta, with the operation order of Gymnasium's rk4() in
// classic_control/acrobot.py: y + h/6 (k1 + 2 k2 + 2 k3 + k4), so that results agree closely.
template <std::size_t N, typename T, typename F>
std::array<T, N> rk4Step(const std::array<T, N>& y, double h, F&& f) {
  const double half = h / 2.0;
  std::array<T, N> tmp;
  const std::array<T, N> k1 = f(y);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + half * k1[i];
  const std::array<T, N> k2 = f(tmp);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + half * k2[i];
  const std::array<T, N> k3 = f(tmp);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + h * k3[i];
  const std::array<T, N> k4 = f(tmp);
  const double sixth = h / 6.0;
  std::array<T, N> out;
  for (std::size_t i = 0; i < N; ++i) {
    out[i] = y[i] + sixth * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  return out;
}

template <std::size_t N, typename T, typename F>
std::array<T, N> integrateStep(Integrator integrator, const std::array<T, N>& y, double h, F&& f) {
  return integrator == Integrator::Euler ? eulerStep<N>(y, h, f) : rk4Step<N>(y, h, f);
}

}  // namespace gpfd::env
