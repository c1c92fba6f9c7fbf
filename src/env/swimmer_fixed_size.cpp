#include "gpfd/env/swimmer_fixed_size.hpp"

#include <cmath>
#include <utility>

#include "gpfd/env/angles.hpp"

namespace gpfd::env {
namespace {

// Solves a x = b (x into b) for symmetric positive definite a, from its lower triangle, by
// a = L D L^T without pivoting.
template <int N>
void solveLdlt(double (&a)[N][N], double (&b)[N]) {
  double inverseD[N];
  for (int j = 0; j < N; ++j) {
    double d = a[j][j];
    for (int k = 0; k < j; ++k) d -= a[j][k] * a[j][k] * a[k][k];
    a[j][j] = d;
    inverseD[j] = 1.0 / d;
    for (int i = j + 1; i < N; ++i) {
      double v = a[i][j];
      for (int k = 0; k < j; ++k) v -= a[i][k] * a[j][k] * a[k][k];
      a[i][j] = v * inverseD[j];
    }
  }
  for (int i = 0; i < N; ++i) {
    for (int k = 0; k < i; ++k) b[i] -= a[i][k] * b[k];
  }
  for (int i = 0; i < N; ++i) b[i] *= inverseD[i];
  for (int i = N - 1; i >= 0; --i) {
    for (int k = i + 1; k < N; ++k) b[i] -= a[k][i] * b[k];
  }
}

// The expressions of Swimmer::derivativeReference, regrouped: the same up to rounding.
template <int N>
void derivativeN(const SwimmerBody& body, const double* s, const double* torque, double* out) {
  double cosine[N], sine[N], forceX[N], forceY[N];
  for (int i = 0; i < N; ++i) {
    cosine[i] = std::cos(s[2 + 2 * i]);
    sine[i] = std::sin(s[2 + 2 * i]);
  }
  // Centre velocities G'_i relative to A'_0 = 0, then shifted so that sum m_i G'_i / M = G'.
  double ax = 0.0, ay = 0.0, meanX = 0.0, meanY = 0.0;
  for (int i = 0; i < N; ++i) {
    const double rate = body.length[i] * s[3 + 2 * i];
    const double nextX = ax - rate * sine[i], nextY = ay + rate * cosine[i];
    forceX[i] = 0.5 * (ax + nextX);  // G'_i for now; turned into the drag force below.
    forceY[i] = 0.5 * (ay + nextY);
    meanX += body.mass[i] * forceX[i];
    meanY += body.mass[i] * forceY[i];
    ax = nextX;
    ay = nextY;
  }
  const double shiftX = s[0] - meanX * body.inverseTotalMass,
               shiftY = s[1] - meanY * body.inverseTotalMass;
  // Normal drag F_i = -k l_i (G'_i . n_i) n_i, n_i = (-sin, cos).
  double sumFx = 0.0, sumFy = 0.0;
  for (int i = 0; i < N; ++i) {
    const double vx = forceX[i] + shiftX, vy = forceY[i] + shiftY;
    const double normal = body.dragFactor[i] * (-vx * sine[i] + vy * cosine[i]);
    forceX[i] = -normal * sine[i];
    forceY[i] = normal * cosine[i];
    sumFx += forceX[i];
    sumFy += forceY[i];
  }
  const double gxx = sumFx * body.inverseTotalMass, gyy = sumFy * body.inverseTotalMass;
  // The system matrix is symmetric positive definite (the rotational mass matrix); only its lower
  // triangle is built. Per pair: cos(th_i - th_j) = c_i c_j + s_i s_j, and
  // sin(th_j - th_i) = c_i s_j - s_i c_j, which is exactly negated when i and j swap.
  double system[N][N], rhs[N], centripetal[N], rateSquared[N];
  for (int i = 0; i < N; ++i) {
    rateSquared[i] = s[3 + 2 * i] * s[3 + 2 * i];
    centripetal[i] = 0.0;  // sum_j C_ij l_j th'_j^2 sin(th_j - th_i); the j = i term is 0.
  }
  for (int i = 0; i < N; ++i) {
    const double ci = cosine[i], si = sine[i];
    for (int j = 0; j < i; ++j) {
      const double cosDiff = ci * cosine[j] + si * sine[j];
      const double sinDiff = ci * sine[j] - si * cosine[j];
      system[i][j] = body.matrixCoupling[i * SwimmerBody::kMax + j] * cosDiff;
      centripetal[i] +=
          body.centripetalCoupling[i * SwimmerBody::kMax + j] * rateSquared[j] * sinDiff;
      centripetal[j] -=
          body.centripetalCoupling[j * SwimmerBody::kMax + i] * rateSquared[i] * sinDiff;
    }
    system[i][i] =
        body.inertia[i] + body.matrixCoupling[i * SwimmerBody::kMax + i] * (ci * ci + si * si);
  }
  double prefixX = 0.0, prefixY = 0.0;
  for (int i = 0; i < N; ++i) {
    const double li = body.length[i], ci = cosine[i], si = sine[i];
    const double halfX = prefixX + 0.5 * forceX[i], halfY = prefixY + 0.5 * forceY[i];
    prefixX += forceX[i];
    prefixY += forceY[i];
    double row = body.viscousMoment[i] * s[3 + 2 * i];
    if (i > 0) row += torque[i - 1];
    if (i + 1 < N) row -= torque[i];
    row += li * body.massWeight[i] * (ci * gyy - si * gxx);
    row -= li * (ci * halfY - si * halfX);
    row -= li * centripetal[i];
    rhs[i] = row;
  }
  solveLdlt<N>(system, rhs);
  out[0] = gxx;
  out[1] = gyy;
  for (int i = 0; i < N; ++i) {
    out[2 + 2 * i] = s[3 + 2 * i];
    out[3 + 2 * i] = rhs[i];
  }
}

// Euler or RK4 with the operation order of Swimmer::integrateReference.
template <int N>
void integrateN(const SwimmerBody& body, Integrator integrator, double h, int substeps,
                double* state, const double* torque) {
  constexpr int dim = 2 * N + 2;
  double y[dim], k1[dim];
  for (int i = 0; i < dim; ++i) y[i] = state[i];
  for (int step = 0; step < substeps; ++step) {
    if (integrator == Integrator::Euler) {
      derivativeN<N>(body, y, torque, k1);
      for (int i = 0; i < dim; ++i) y[i] += h * k1[i];
    } else {
      double k2[dim], k3[dim], k4[dim], tmp[dim];
      const double half = h / 2.0;
      derivativeN<N>(body, y, torque, k1);
      for (int i = 0; i < dim; ++i) tmp[i] = y[i] + half * k1[i];
      derivativeN<N>(body, tmp, torque, k2);
      for (int i = 0; i < dim; ++i) tmp[i] = y[i] + half * k2[i];
      derivativeN<N>(body, tmp, torque, k3);
      for (int i = 0; i < dim; ++i) tmp[i] = y[i] + h * k3[i];
      derivativeN<N>(body, tmp, torque, k4);
      const double sixth = h / 6.0;
      for (int i = 0; i < dim; ++i) y[i] += sixth * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    for (int i = 0; i < N; ++i) y[2 + 2 * i] = wrapAngle(y[2 + 2 * i]);
  }
  for (int i = 0; i < dim; ++i) state[i] = y[i];
}

using DerivativeFn = void (*)(const SwimmerBody&, const double*, const double*, double*);
using IntegrateFn = void (*)(const SwimmerBody&, Integrator, double, int, double*, const double*);

template <int... N>
constexpr auto derivativeTable(std::integer_sequence<int, N...>) {
  return std::array<DerivativeFn, sizeof...(N)>{&derivativeN<N + 2>...};
}
template <int... N>
constexpr auto integrateTable(std::integer_sequence<int, N...>) {
  return std::array<IntegrateFn, sizeof...(N)>{&integrateN<N + 2>...};
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
