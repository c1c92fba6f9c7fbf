// env: the swimmer's dynamics for up to kSwimmerFixedMaxSegments segments, with the segment count
// a compile-time constant: stack arrays only, no heap allocation, each sin/cos once per angle, the
// symmetric positive definite n x n system (the rotational mass matrix I + l_i l_j D_ij
// cos(th_i - th_j), D = -C a Gram matrix) built as its lower triangle and solved by an unpivoted
// L D L^T. Equal to Swimmer::derivativeReference up to rounding: tests/env/test_swimmer.cpp
// checks 1e-12 relative to the largest component.
#pragma once

#include <array>

#include "gpfd/env/integrate.hpp"

namespace gpfd::env {

inline constexpr int kSwimmerFixedMaxSegments = 8;

// Constants of the body (see docs/environments.md, "The swimmer's linear system"). Row-major
// kMax x kMax arrays of which the leading n x n block is used. C must be symmetric.
struct SwimmerBody {
  static constexpr int kMax = kSwimmerFixedMaxSegments;
  int segments = 0;
  double inverseTotalMass = 0.0;  // 1 / M.
  std::array<double, kMax> mass{}, length{}, inertia{};
  std::array<double, kMax> dragFactor{};     // -k l_i: F_i = dragFactor_i (G'_i . n_i) n_i.
  std::array<double, kMax> viscousMoment{};  // -k l_i^3 / 12: M_i = viscousMoment_i th'_i.
  std::array<double, kMax> massWeight{};     // W_i = sum_k w_ik m_k.
  // -l_i l_j C_ij: the system matrix is this times cos(th_i - th_j), plus I_i on the diagonal.
  std::array<double, kMax * kMax> matrixCoupling{};
  // C_ij l_j: the centripetal term of row i is sum_j of this times th'_j^2 sin(th_j - th_i).
  std::array<double, kMax * kMax> centripetalCoupling{};
};

// d/dt state (2n + 2 values) at `state` under joint torques `torque` (n - 1 values), into `out`.
// Requires 2 <= body.segments <= kSwimmerFixedMaxSegments.
void swimmerFixedDerivative(const SwimmerBody& body, const double* state, const double* torque,
                            double* out);

// `substeps` integration steps of h seconds on `state` in place, torques held; every angle is
// wrapped into [-pi, pi] after each step. Requires 2 <= body.segments <= kSwimmerFixedMaxSegments.
void swimmerFixedIntegrate(const SwimmerBody& body, Integrator integrator, double h, int substeps,
                           double* state, const double* torque);

}  // namespace gpfd::env
