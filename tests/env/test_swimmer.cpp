// The n-segment swimmer: the solved dynamics against an independent formulation, conservation
// laws, rotation invariance and forward swimming under a travelling wave.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <string>

#include "gpfd/env/swimmer.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

constexpr double kPi = std::numbers::pi;

// Straight from the equations of docs/benchmarks.md, without eliminating anything: unknowns A''_0
// (2), th''_1..n (n) and the internal forces f_1..f_{n-1} (2 each), with f_0 = f_n = 0; equations
// m_i G''_i = F_i + f_i - f_{i-1} (2n) and the n rotation equations. Returns (G''x, G''y, th''...).
std::vector<double> referenceAccelerations(int n, double k, const std::vector<double>& s,
                                           const std::vector<double>& u) {
  const int unknowns = 3 * n;
  const double m = 1.0, l = 1.0, inertia = 1.0 / 12.0, total = n * m;
  std::vector<double> c(n), sn(n), w(n);
  for (int i = 0; i < n; ++i) {
    c[i] = std::cos(s[2 + 2 * i]);
    sn[i] = std::sin(s[2 + 2 * i]);
    w[i] = s[3 + 2 * i];
  }
  // Velocities: A'_i = A'_{i-1} + l th'_i n_i from A'_0 = 0, then shifted so the mean is G'.
  std::vector<Eigen::Vector2d> gv(n);
  Eigen::Vector2d a(0, 0), mean(0, 0);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d next = a + l * w[i] * Eigen::Vector2d(-sn[i], c[i]);
    gv[i] = (a + next) / 2;
    mean += m * gv[i] / total;
    a = next;
  }
  std::vector<Eigen::Vector2d> drag(n);
  for (int i = 0; i < n; ++i) {
    gv[i] += Eigen::Vector2d(s[0], s[1]) - mean;
    const Eigen::Vector2d normal(-sn[i], c[i]);
    drag[i] = -k * l * gv[i].dot(normal) * normal;
  }
  // G''_i as rows over the unknowns plus a constant.
  const auto ddth = [](int i) { return 2 + i; };
  const auto force = [n](int i) { return 2 + n + 2 * (i - 1); };  // f_i, 1 <= i <= n-1.
  std::vector<Eigen::MatrixXd> gRows(n, Eigen::MatrixXd::Zero(2, unknowns));
  std::vector<Eigen::Vector2d> gConst(n, Eigen::Vector2d::Zero());
  Eigen::MatrixXd aRow = Eigen::MatrixXd::Zero(2, unknowns);
  aRow(0, 0) = 1;
  aRow(1, 1) = 1;
  Eigen::Vector2d aConst(0, 0);
  for (int i = 0; i < n; ++i) {
    Eigen::MatrixXd nextRow = aRow;
    nextRow(0, ddth(i)) += -l * sn[i];
    nextRow(1, ddth(i)) += l * c[i];
    const Eigen::Vector2d nextConst = aConst - l * w[i] * w[i] * Eigen::Vector2d(c[i], sn[i]);
    gRows[i] = (aRow + nextRow) / 2;
    gConst[i] = (aConst + nextConst) / 2;
    aRow = nextRow;
    aConst = nextConst;
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(unknowns, unknowns);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(unknowns);
  int row = 0;
  for (int i = 1; i <= n; ++i) {  // f_i - f_{i-1} - m G''_i = -F_i
    for (int d = 0; d < 2; ++d, ++row) {
      if (i <= n - 1) A(row, force(i) + d) += 1;
      if (i - 1 >= 1) A(row, force(i - 1) + d) -= 1;
      A.row(row) -= m * gRows[i - 1].row(d);
      b(row) = -drag[i - 1](d) + m * gConst[i - 1](d);
    }
  }
  for (int i = 1; i <= n; ++i, ++row) {  // I th''_i - (l/2) p_i x (f_{i-1} + f_i) = M_i + u's
    const double px = c[i - 1], py = sn[i - 1];
    A(row, ddth(i - 1)) += inertia;
    for (int j : {i - 1, i}) {
      if (j < 1 || j > n - 1) continue;
      A(row, force(j) + 1) -= l / 2 * px;  // p x f = px fy - py fx
      A(row, force(j)) += l / 2 * py;
    }
    b(row) = -k * w[i - 1] * l * l * l / 12;
    if (i >= 2) b(row) += u[i - 2];
    if (i <= n - 1) b(row) -= u[i - 1];
  }
  const Eigen::VectorXd z = A.fullPivLu().solve(b);
  Eigen::Vector2d g(0, 0);
  for (int i = 0; i < n; ++i) g += m * (gRows[i] * z + gConst[i]) / total;
  std::vector<double> out{g(0), g(1)};
  for (int i = 0; i < n; ++i) out.push_back(z(ddth(i)));
  return out;
}

std::vector<double> randomState(Rng& rng, int n) {
  std::vector<double> s{rng.normal(), rng.normal()};
  for (int i = 0; i < n; ++i) {
    s.push_back(rng.uniform(-kPi, kPi));
    s.push_back(2 * rng.normal());
  }
  return s;
}

std::vector<double> accelerations(Swimmer& sw, const std::vector<double>& s,
                                  const std::vector<double>& u) {
  std::vector<double> d(s.size());
  sw.derivative(s, u, d);
  std::vector<double> out{d[0], d[1]};
  for (int i = 0; i < sw.segments(); ++i) out.push_back(d[3 + 2 * i]);
  return out;
}

TEST(Swimmer, MatchesAnIndependentSolutionForTwoToSixSegments) {
  Rng rng(21);
  for (int n = 2; n <= 6; ++n) {
    SwimmerConfig config;
    config.segments = n;
    Swimmer sw(config);
    for (int trial = 0; trial < 50; ++trial) {
      const auto s = randomState(rng, n);
      std::vector<double> u;
      for (int j = 0; j < n - 1; ++j) u.push_back(rng.uniform(-5, 5));
      const auto got = accelerations(sw, s, u);
      const auto want = referenceAccelerations(n, 10.0, s, u);
      std::vector<double> d(s.size());
      sw.derivativeReference(s, u, d);
      std::vector<double> gotReference{d[0], d[1]};
      for (int i = 0; i < n; ++i) gotReference.push_back(d[3 + 2 * i]);
      ASSERT_EQ(got.size(), want.size());
      for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_NEAR(got[i], want[i], 1e-9 * std::max(1.0, std::fabs(want[i])))
            << "n=" << n << " trial " << trial << " index " << i;
        EXPECT_NEAR(gotReference[i], want[i], 1e-9 * std::max(1.0, std::fabs(want[i])))
            << "reference solver, n=" << n << " trial " << trial << " index " << i;
      }
    }
  }
}

std::string scientific(double x) {
  std::ostringstream out;
  out << std::scientific << std::setprecision(2) << x;
  return out.str();
}

// |got_i - want_i| <= 1e-12 max_j |want_j| for every component (the fixed-size kernel against
// the original Eigen LU solve it replaced: the same equations, rounded differently); returns the
// largest difference seen relative to that scale.
double expectSameWithin1e12(std::span<const double> got, std::span<const double> want,
                            const std::string& where) {
  EXPECT_EQ(got.size(), want.size()) << where;
  double scale = 0.0;
  for (double v : want) scale = std::max(scale, std::fabs(v));
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(got.size(), want.size()); ++i) {
    const double diff = std::fabs(got[i] - want[i]);
    EXPECT_LE(diff, 1e-12 * scale) << where << " index " << i;
    if (diff > 0.0) worst = std::max(worst, diff / scale);
  }
  return worst;
}

TEST(Swimmer, FixedSizeDerivativeMatchesTheReferenceSolve) {
  Rng rng(34);
  double worst = 0.0;
  for (int n = 2; n <= kSwimmerFixedMaxSegments + 1; ++n) {  // n = 9 takes the reference path.
    for (const double k : {10.0, 0.0}) {
      SwimmerConfig config;
      config.segments = n;
      config.viscosity = k;
      Swimmer sw(config);
      for (int trial = 0; trial < 200; ++trial) {
        auto s = randomState(rng, n);
        if (trial % 4 == 3) {
          for (double& v : s) v *= 10.0;  // Angles beyond [-pi, pi], fast rotation.
        }
        std::vector<double> u;
        for (int j = 0; j < n - 1; ++j) u.push_back(rng.uniform(-5, 5));
        std::vector<double> got(s.size()), want(s.size());
        sw.derivative(s, u, got);
        sw.derivativeReference(s, u, want);
        worst = std::max(worst,
                         expectSameWithin1e12(got, want,
                                              "n=" + std::to_string(n) + " k=" + std::to_string(k) +
                                                  " trial " + std::to_string(trial)));
      }
    }
  }
  RecordProperty("largest_relative_difference", scientific(worst));
}

TEST(Swimmer, FixedSizeStepMatchesTheReferenceStep) {
  Rng rng(55);
  double worst = 0.0;
  for (int n = 2; n <= 6; ++n) {
    for (const char* integrator : {"euler", "rk4"}) {
      const Params params{
          {"segments", std::to_string(n)}, {"integrator", integrator}, {"horizon", "0"}};
      Swimmer fast(SwimmerConfig::fromParams(params));
      Swimmer reference(SwimmerConfig::fromParams(params));
      reference.setReferenceSolver(true);
      reference.setState(randomState(rng, n));
      std::vector<double> u(static_cast<std::size_t>(n - 1));
      // Along a random-action trajectory of the reference, one step of each from the same state.
      for (int t = 0; t < 50; ++t) {
        fast.setState(reference.state());
        reference.sampleAction(rng, u);
        const double fastReward = fast.step(u).reward;
        const double referenceReward = reference.step(u).reward;
        const std::string where =
            "n=" + std::to_string(n) + " " + integrator + " step " + std::to_string(t);
        worst = std::max(worst, expectSameWithin1e12(fast.state(), reference.state(), where));
        EXPECT_LE(std::fabs(fastReward - referenceReward), 1e-12 * std::fabs(referenceReward))
            << where;
      }
    }
  }
  RecordProperty("largest_relative_difference", scientific(worst));
}

TEST(Swimmer, StateNamesActionSpaceAndReset) {
  Swimmer sw(SwimmerConfig::fromParams({{"segments", "5"}}));
  EXPECT_EQ(sw.stateDim(), 12u);
  EXPECT_EQ(sw.stateNames()[2], "th1");
  EXPECT_EQ(sw.stateNames()[11], "dth5");
  const ActionSpace space = sw.actionSpace();
  EXPECT_EQ(space.components, 4u);
  EXPECT_EQ(space.high[3], 5.0);
  Rng rng(1);
  sw.reset(rng);
  for (std::size_t i = 0; i < sw.stateDim(); ++i) {
    if (i >= 2 && i % 2 == 0) {
      EXPECT_LE(std::fabs(sw.state()[i]), 0.1);
    } else {
      EXPECT_EQ(sw.state()[i], 0.0);
    }
  }
  EXPECT_THROW(SwimmerConfig::fromParams({{"segments", "1"}}), InputError);
  EXPECT_THROW(sw.setState(std::vector<double>(11, 0.0)), InputError);
  EXPECT_THROW(sw.step(std::vector<double>(3, 0.0)), InputError);
}

// Kinetic energy and angular momentum about G, from the state.
struct Invariants {
  double energy = 0.0;
  double angularMomentum = 0.0;
};

Invariants invariants(std::span<const double> s, int n) {
  std::vector<Eigen::Vector2d> pos(n), vel(n);
  Eigen::Vector2d a(0, 0), av(0, 0), meanPos(0, 0), meanVel(0, 0);
  for (int i = 0; i < n; ++i) {
    const double th = s[2 + 2 * i], w = s[3 + 2 * i];
    const Eigen::Vector2d next = a + Eigen::Vector2d(std::cos(th), std::sin(th));
    const Eigen::Vector2d nextV = av + w * Eigen::Vector2d(-std::sin(th), std::cos(th));
    pos[i] = (a + next) / 2;
    vel[i] = (av + nextV) / 2;
    meanPos += pos[i] / n;
    meanVel += vel[i] / n;
    a = next;
    av = nextV;
  }
  Invariants out;
  const Eigen::Vector2d g(s[0], s[1]);
  out.energy = 0.5 * n * g.squaredNorm();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d r = pos[i] - meanPos, v = vel[i] - meanVel;
    const double w = s[3 + 2 * i];
    out.angularMomentum += w / 12.0 + (r.x() * v.y() - r.y() * v.x());
    out.energy += 0.5 * (v + g).squaredNorm() - 0.5 * g.squaredNorm() + 0.5 * w * w / 12.0;
  }
  return out;
}

TEST(Swimmer, WithoutDragMomentumAndAngularMomentumAreConserved) {
  Swimmer sw(SwimmerConfig::fromParams({{"segments", "4"},
                                        {"viscosity", "0"},
                                        {"integrator", "rk4"},
                                        {"dt", "0.01"},
                                        {"substeps", "4"},
                                        {"horizon", "0"}}));
  Rng rng(8);
  const auto start = randomState(rng, 4);
  sw.setState(start);
  const double l0 = invariants(sw.state(), 4).angularMomentum;
  for (int t = 0; t < 300; ++t) {
    std::vector<double> u{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)};
    sw.step(u);  // Joint torques are internal: they change neither momentum.
    ASSERT_NEAR(sw.state()[0], start[0], 1e-12);
    ASSERT_NEAR(sw.state()[1], start[1], 1e-12);
  }
  EXPECT_NEAR(invariants(sw.state(), 4).angularMomentum, l0, 1e-6 * std::max(1.0, std::fabs(l0)));
}

TEST(Swimmer, WithDragAndNoTorqueMomentumDecaysOnlyThroughDrag) {
  Swimmer sw(SwimmerConfig::fromParams({{"segments", "3"},
                                        {"integrator", "rk4"},
                                        {"dt", "0.01"},
                                        {"substeps", "1"},
                                        {"horizon", "0"}}));
  sw.setState(std::vector<double>{1.0, 0.5, 0.2, 0.5, -0.3, -1.0, 0.4, 2.0});
  const std::vector<double> zero(2, 0.0);
  double energy = invariants(sw.state(), 3).energy;
  const double speed0 = std::hypot(sw.state()[0], sw.state()[1]);
  for (int t = 0; t < 500; ++t) {
    // G'' = sum F_i / M, the drag alone: check it against the drag computed here.
    std::vector<double> s(sw.state().begin(), sw.state().end()), d(s.size());
    sw.derivative(s, zero, d);
    const auto ref = referenceAccelerations(3, 10.0, s, zero);
    ASSERT_NEAR(d[0], ref[0], 1e-10);
    ASSERT_NEAR(d[1], ref[1], 1e-10);
    sw.step(zero);
    const double e = invariants(sw.state(), 3).energy;
    ASSERT_LE(e, energy + 1e-12) << "step " << t;  // Drag only dissipates.
    energy = e;
  }
  // Only normal drag: motion along the body axis decays only as the body bends, so slowly.
  EXPECT_LT(std::hypot(sw.state()[0], sw.state()[1]), 0.1 * speed0);
}

TEST(Swimmer, RotatingTheWholeBodyRotatesTheMotion) {
  Rng rng(5);
  Swimmer sw(SwimmerConfig::fromParams({{"segments", "5"}}));
  for (int trial = 0; trial < 20; ++trial) {
    const auto s = randomState(rng, 5);
    const std::vector<double> u{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5),
                                rng.uniform(-5, 5)};
    const double alpha = rng.uniform(-kPi, kPi), ca = std::cos(alpha), sa = std::sin(alpha);
    auto r = s;
    r[0] = ca * s[0] - sa * s[1];
    r[1] = sa * s[0] + ca * s[1];
    for (int i = 0; i < 5; ++i) r[2 + 2 * i] += alpha;
    const auto a = accelerations(sw, s, u);
    const auto b = accelerations(sw, r, u);
    EXPECT_NEAR(b[0], ca * a[0] - sa * a[1], 1e-9 * std::max(1.0, std::fabs(b[0])));
    EXPECT_NEAR(b[1], sa * a[0] + ca * a[1], 1e-9 * std::max(1.0, std::fabs(b[1])));
    for (int i = 2; i < 7; ++i) EXPECT_NEAR(b[i], a[i], 1e-9 * std::max(1.0, std::fabs(a[i])));
  }
}

// Mean dGx over `steps` steps under u_j(t) = 5 sin(2 pi t / period - direction * 2 pi j / n),
// starting straight along -x from the head (th_i = pi: the head is at the +x end).
double meanVelocityUnderWave(int n, double direction, int steps) {
  Swimmer sw(SwimmerConfig::fromParams({{"segments", std::to_string(n)}, {"horizon", "0"}}));
  std::vector<double> s(2 + 2 * n, 0.0);
  for (int i = 0; i < n; ++i) s[2 + 2 * i] = kPi;
  sw.setState(s);
  std::vector<double> u(n - 1);
  double sum = 0.0;
  for (int t = 0; t < steps; ++t) {
    const double time = t * sw.config().dt;
    for (int j = 1; j < n; ++j) {
      u[j - 1] = 5.0 * std::sin(2 * kPi * time / 1.0 - direction * 2 * kPi * j / n);
    }
    const StepResult r = sw.step(u);
    EXPECT_NEAR(r.reward, sw.state()[0] * sw.config().dt, 1e-15);
    sum += sw.state()[0];
  }
  return sum / steps;
}

TEST(Swimmer, SwimsHeadFirstUnderAWaveTravellingFromHeadToTail) {
  for (int n : {3, 5}) {
    const double forward = meanVelocityUnderWave(n, +1.0, 300);
    const double backward = meanVelocityUnderWave(n, -1.0, 300);
    RecordProperty("mean_dGx_n" + std::to_string(n), std::to_string(forward));
    EXPECT_GT(forward, 0.01) << "n=" << n;
    EXPECT_LT(backward, -0.01) << "n=" << n;
  }
}

TEST(Swimmer, SameSeedSameTrajectoryAndAnglesStayWrapped) {
  const auto run = [](std::uint64_t seed) {
    Swimmer sw(SwimmerConfig::fromParams({{"segments", "3"}}));
    Rng rng(seed);
    sw.reset(rng);
    std::vector<double> trace, u(2);
    for (int t = 0; t < 100; ++t) {
      sw.sampleAction(rng, u);
      sw.step(u);
      for (int i = 0; i < 3; ++i) EXPECT_LE(std::fabs(sw.state()[2 + 2 * i]), kPi);
      trace.insert(trace.end(), sw.state().begin(), sw.state().end());
    }
    return trace;
  };
  EXPECT_EQ(run(1), run(1));
  EXPECT_NE(run(1), run(2));
}

}  // namespace
}  // namespace gpfd::env
