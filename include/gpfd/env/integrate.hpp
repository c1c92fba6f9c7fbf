// env: one explicit integration step of an autonomous ODE dy/dt = f(y) over fixed-size states.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "gpfd/util/params.hpp"

namespace gpfd::env {

enum class Integrator { Euler, Rk4 };

// The integration parameters of a simulated environment, declared in its parameter table over
// config fields of the same names: `integrator` (euler | rk4; `integrators` says which source uses
// which), `dt` (the control interval in seconds, in [1e-4, 10]; the action is held over it) and
// `substeps` (integration steps per interval, in [1, 10000]; `substepsMeaning`), and the rule
// that the integration step dt / substeps is at most maxStep(config) seconds, beyond which the
// integrator no longer follows the dynamics (`limit` says what the bound is and why).
template <typename Config, typename MaxStep>
void declareIntegration(ParamTable<Config>& table, const std::string& integrators,
                        const std::string& substepsMeaning, MaxStep maxStep,
                        const std::string& limit) {
  table
      .choice(
          "integrator", [](auto& c) -> auto& { return c.integrator; },
          std::vector<std::pair<std::string, Integrator>>{{"euler", Integrator::Euler},
                                                          {"rk4", Integrator::Rk4}},
          integrators)
      .real(
          "dt", [](auto& c) -> auto& { return c.dt; }, 1e-4, 10.0,
          "control interval in seconds; the action is held over it")
      .integer(
          "substeps", [](auto& c) -> auto& { return c.substeps; }, 1, 10000, substepsMeaning)
      .rule(
          "substeps",
          [maxStep](const Config& c) {
            return c.dt / c.substeps <= maxStep(c) * (1 + 1e-12);  // Rounding at the edge.
          },
          "the integration step dt / substeps is too long: " + limit + "; raise substeps");
}

template <std::size_t N>
using Vec = std::array<double, N>;

// Explicit Euler: y + h f(y).
template <std::size_t N, typename F>
Vec<N> eulerStep(const Vec<N>& y, double h, F&& f) {
  const Vec<N> k = f(y);
  Vec<N> out;
  for (std::size_t i = 0; i < N; ++i) out[i] = y[i] + h * k[i];
  return out;
}

// Classical fourth-order Runge-Kutta, with the operation order of Gymnasium's rk4() in
// classic_control/acrobot.py: y + h/6 (k1 + 2 k2 + 2 k3 + k4), so that results agree closely.
template <std::size_t N, typename F>
Vec<N> rk4Step(const Vec<N>& y, double h, F&& f) {
  const double half = h / 2.0;
  Vec<N> tmp;
  const Vec<N> k1 = f(y);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + half * k1[i];
  const Vec<N> k2 = f(tmp);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + half * k2[i];
  const Vec<N> k3 = f(tmp);
  for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + h * k3[i];
  const Vec<N> k4 = f(tmp);
  const double sixth = h / 6.0;
  Vec<N> out;
  for (std::size_t i = 0; i < N; ++i) {
    out[i] = y[i] + sixth * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  return out;
}

template <std::size_t N, typename F>
Vec<N> integrateStep(Integrator integrator, const Vec<N>& y, double h, F&& f) {
  return integrator == Integrator::Euler ? eulerStep<N>(y, h, f) : rk4Step<N>(y, h, f);
}

}  // namespace gpfd::env
