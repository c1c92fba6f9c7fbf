// env: the swimmer's fixed-size kernel (swimmer_fixed_size.hpp) written once over the number type T
// (double for Swimmer, Lanes4 for four lanes of the batched swimmer), so that every lane gives
// Swimmer's bits.
#pragma once

#include "gpfd/env/angles.hpp"
#include "gpfd/env/swimmer_fixed_size.hpp"
#include "gpfd/expr/trig_lanes.hpp"

namespace gpfd::env::swimmer {

// Solves a x = b (x into b) for symmetric positive definite a, from its lower triangle, by
// a = L D L^T without pivoting.
template <int N, class T>
void solveLdlt(T (&a)[N][N], T (&b)[N]) {
  T inverseD[N];
  for (int j = 0; j < N; ++j) {
    T d = a[j][j];
    for (int k = 0; k < j; ++k) d -= a[j][k] * a[j][k] * a[k][k];
    a[j][j] = d;
    inverseD[j] = 1.0 / d;
    for (int i = j + 1; i < N; ++i) {
      T v = a[i][j];
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
template <int N, class T>
void derivativeN(const SwimmerBody& body, const T* s, const T* torque, T* out) {
  T cosine[N], sine[N], forceX[N], forceY[N];
  for (int i = 0; i < N; ++i) {
    const auto [sinTh, cosTh] = expr::trig::sinCos(s[2 + 2 * i]);
    cosine[i] = cosTh;
    sine[i] = sinTh;
  }
  // Centre velocities G'_i relative to A'_0 = 0, then shifted so that sum m_i G'_i / M = G'.
  T ax = 0.0, ay = 0.0, meanX = 0.0, meanY = 0.0;
  for (int i = 0; i < N; ++i) {
    const T rate = body.length[i] * s[3 + 2 * i];
    const T nextX = ax - rate * sine[i], nextY = ay + rate * cosine[i];
    forceX[i] = 0.5 * (ax + nextX);  // G'_i for now; turned into the drag force below.
    forceY[i] = 0.5 * (ay + nextY);
    meanX += body.mass[i] * forceX[i];
    meanY += body.mass[i] * forceY[i];
    ax = nextX;
    ay = nextY;
  }
  const T shiftX = s[0] - meanX * body.inverseTotalMass,
          shiftY = s[1] - meanY * body.inverseTotalMass;
  // Normal drag F_i = -k l_i (G'_i . n_i) n_i, n_i = (-sin, cos).
  T sumFx = 0.0, sumFy = 0.0;
  for (int i = 0; i < N; ++i) {
    const T vx = forceX[i] + shiftX, vy = forceY[i] + shiftY;
    const T normal = body.dragFactor[i] * (-vx * sine[i] + vy * cosine[i]);
    forceX[i] = -normal * sine[i];
    forceY[i] = normal * cosine[i];
    sumFx += forceX[i];
    sumFy += forceY[i];
  }
  const T gxx = sumFx * body.inverseTotalMass, gyy = sumFy * body.inverseTotalMass;
  // The system matrix is symmetric positive definite (the rotational mass matrix); only its lower
  // triangle is built. Per pair: cos(th_i - th_j) = c_i c_j + s_i s_j, and
  // sin(th_j - th_i) = c_i s_j - s_i c_j, which is exactly negated when i and j swap.
  T system[N][N], rhs[N], centripetal[N], rateSquared[N];
  for (int i = 0; i < N; ++i) {
    rateSquared[i] = s[3 + 2 * i] * s[3 + 2 * i];
    centripetal[i] = 0.0;  // sum_j C_ij l_j th'_j^2 sin(th_j - th_i); the j = i term is 0.
  }
  for (int i = 0; i < N; ++i) {
    const T ci = cosine[i], si = sine[i];
    for (int j = 0; j < i; ++j) {
      const T cosDiff = ci * cosine[j] + si * sine[j];
      const T sinDiff = ci * sine[j] - si * cosine[j];
      system[i][j] = body.matrixCoupling[i * SwimmerBody::kMax + j] * cosDiff;
      centripetal[i] +=
          body.centripetalCoupling[i * SwimmerBody::kMax + j] * rateSquared[j] * sinDiff;
      centripetal[j] -=
          body.centripetalCoupling[j * SwimmerBody::kMax + i] * rateSquared[i] * sinDiff;
    }
    system[i][i] =
        body.inertia[i] + body.matrixCoupling[i * SwimmerBody::kMax + i] * (ci * ci + si * si);
  }
  T prefixX = 0.0, prefixY = 0.0;
  for (int i = 0; i < N; ++i) {
    const double li = body.length[i];
    const T ci = cosine[i], si = sine[i];
    const T halfX = prefixX + 0.5 * forceX[i], halfY = prefixY + 0.5 * forceY[i];
    prefixX += forceX[i];
    prefixY += forceY[i];
    T row = body.viscousMoment[i] * s[3 + 2 * i];
    if (i > 0) row += torque[i - 1];
    if (i + 1 < N) row -= torque[i];
    row += li * body.massWeight[i] * (ci * gyy - si * gxx);
    row -= li * (ci * halfY - si * halfX);
    row -= li * centripetal[i];
    rhs[i] = row;
  }
  solveLdlt<N, T>(system, rhs);
  out[0] = gxx;
  out[1] = gyy;
  for (int i = 0; i < N; ++i) {
    out[2 + 2 * i] = s[3 + 2 * i];
    out[3 + 2 * i] = rhs[i];
  }
}

// Euler or RK4 with the operation order of Swimmer::integrateReference.
template <int N, class T>
void integrateN(const SwimmerBody& body, Integrator integrator, double h, int substeps, T* state,
                const T* torque) {
  constexpr int dim = 2 * N + 2;
  T y[dim], k1[dim];
  for (int i = 0; i < dim; ++i) y[i] = state[i];
  for (int step = 0; step < substeps; ++step) {
    if (integrator == Integrator::Euler) {
      derivativeN<N, T>(body, y, torque, k1);
      for (int i = 0; i < dim; ++i) y[i] += h * k1[i];
    } else {
      T k2[dim], k3[dim], k4[dim], tmp[dim];
      const double half = h / 2.0;
      derivativeN<N, T>(body, y, torque, k1);
      for (int i = 0; i < dim; ++i) tmp[i] = y[i] + half * k1[i];
      derivativeN<N, T>(body, tmp, torque, k2);
      for (int i = 0; i < dim; ++i) tmp[i] = y[i] + half * k2[i];
      derivativeN<N, T>(body, tmp, torque, k3);
      for (int i = 0; i < dim; ++i) tmp[i] = y[i] + h * k3[i];
      derivativeN<N, T>(body, tmp, torque, k4);
      const double sixth = h / 6.0;
      for (int i = 0; i < dim; ++i) y[i] += sixth * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    for (int i = 0; i < N; ++i) y[2 + 2 * i] = wrapAngle(y[2 + 2 * i]);
  }
  for (int i = 0; i < dim; ++i) state[i] = y[i];
}

}  // namespace gpfd::env::swimmer
