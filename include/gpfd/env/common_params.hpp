// env: the parameters that several environments declare alike, for their ParamTables.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "gpfd/env/integrate.hpp"
#include "gpfd/util/params.hpp"

namespace gpfd::env {

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

// `actions`: continuous (the config's `discrete` false) or discrete; `meaning` says what each is.
template <typename Config>
void declareActionKind(ParamTable<Config>& table, const std::string& meaning) {
  table.choice(
      "actions", [](auto& c) -> auto& { return c.discrete; },
      std::vector<std::pair<std::string, bool>>{{"continuous", false}, {"discrete", true}},
      meaning);
}

// A time limit in `unit`s (a truncation), in [0, 1e9]; 0 = none. `field` returns the member.
template <typename Config, typename Field>
void declareTimeLimit(ParamTable<Config>& table, const std::string& name, Field field,
                      const std::string& unit) {
  table.integer(name, field, 0, 1000000000, "time limit in " + unit + " (truncation); 0 = none");
}

}  // namespace gpfd::env
