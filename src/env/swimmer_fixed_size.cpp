#include "gpfd/env/swimmer_fixed_size.hpp"

#include <utility>

#include "swimmer_kernel.hpp"

namespace gpfd::env {
namespace {

using DerivativeFn = void (*)(const SwimmerBody&, const double*, const double*, double*);
using IntegrateFn = void (*)(const SwimmerBody&, Integrator, double, int, double*, const double*);

template <int... N>
constexpr auto derivativeTable(std::integer_sequence<int, N...>) {
  return std::array<DerivativeFn, sizeof...(N)>{&swimmer::derivativeN<N + 2, double>...};
}
template <int... N>
constexpr auto integrateTable(std::integer_sequence<int, N...>) {
  return std::array<IntegrateFn, sizeof...(N)>{&swimmer::integrateN<N + 2, double>...};
}
// Entry n - 2 serves n segments.
constexpr auto kDerivatives =
    derivativeTable(std::make_integer_sequence<int, kSwimmerFixedMaxSegments - 1>{});
constexpr auto kIntegrators =
    integrateTable(std::make_integer_sequence<int, kSwimmerFixedMaxSegments - 1>{});

}  // namespace

void swimmerFixedDerivative(const SwimmerBody& body, const double* state, const double* torque,
                            double* out) {
  kDerivatives[static_cast<std::size_t>(body.segments - 2)](body, state, torque, out);
}

void swimmerFixedIntegrate(const SwimmerBody& body, Integrator integrator, double h, int substeps,
                           double* state, const double* torque) {
  kIntegrators[static_cast<std::size_t>(body.segments - 2)](body, integrator, h, substeps, state,
                                                            torque);
}

}  // namespace gpfd::env
