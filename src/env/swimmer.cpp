#include "gpfd/env/swimmer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "batch_factories.hpp"
#include "gpfd/env/angles.hpp"
#include "gpfd/env/common_params.hpp"
#include "gpfd/env/snapshot.hpp"
#include "gpfd/expr/trig.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

const ParamTable<SwimmerConfig>& SwimmerConfig::table() {
  static const auto table = [] {
    ParamTable<SwimmerConfig> t("swimmer");
    t.integer(
        "segments", [](auto& c) -> auto& { return c.segments; }, 2, 100,
        "number of segments n (2n + 2 state variables)");
    // The explicit integrators follow the dynamics only while the step resolves the fastest mode,
    // which speeds up with the number of segments and the viscosity; without drag nothing damps
    // the energy that explicit Euler adds. The bounds are empirical, about half of where
    // random-torque runs blow up (docs/environments.md, "Swimmer integration").
    declareIntegration(
        t, "euler: Coulom's; rk4",
        "integration steps per control interval; angles wrapped after each",
        [](const SwimmerConfig& c) {
          const double bound = c.integrator == Integrator::Rk4 ? 0.3
                               : c.viscosity >= 1.0            ? 0.2
                                                               : 0.05;
          return bound / (c.segments * std::max(1.0, c.viscosity / 10.0));
        },
        "h * segments * max(1, viscosity / 10) must be at most 0.2 with euler (0.05 below "
        "viscosity 1) and 0.3 with rk4");
    t.real(
        "max_torque", [](auto& c) -> auto& { return c.maxTorque; }, 1e-3, 100.0,
        "joint torque bound: u_j in [-max_torque, max_torque]");
    declareTimeLimit(
        t, "horizon", [](auto& c) -> auto& { return c.horizon; }, "steps");
    t.real(
         "viscosity", [](auto& c) -> auto& { return c.viscosity; }, 0.0, 100.0,
         "fluid viscosity k of the normal drag")
        .real(
            "start_angle_noise", [](auto& c) -> auto& { return c.startAngleNoise; }, 0.0,
            std::numbers::pi, "reset: at rest, each th_i ~ U(-a, a) (a = this value)");
    return t;
  }();
  return table;
}

EnvInfo Swimmer::info() {
  EnvInfo info{
      "swimmer", "n-segment swimmer in a viscous fluid; swim along x (Coulom 2002, appendix B)",
      SwimmerConfig::table().specs(),
      [](const Params& p) { return std::make_unique<Swimmer>(SwimmerConfig::fromParams(p)); }};
  info.batch = batch::formOf(&batch::makeSwimmer,
                             [](const Swimmer& s) { return s.fixedSizeBody() != nullptr; });
  return info;
}

std::unique_ptr<Environment> Swimmer::freshCopy() const {
  auto copy = std::make_unique<Swimmer>(config_);
  copy->setReferenceSolver(referenceSolver_);
  return copy;
}

Swimmer::Swimmer(SwimmerConfig config) : config_(config), n_(config.segments) {
  if (n_ < 2) throw InputError("the swimmer needs at least 2 segments", "swimmer.segments");
  const auto n = static_cast<std::size_t>(n_);
  names_ = {"dGx", "dGy"};
  for (int i = 1; i <= n_; ++i) {
    names_.push_back(fmt::format("th{}", i));
    names_.push_back(fmt::format("dth{}", i));
  }
  state_.assign(2 * n + 2, 0.0);
  torque_.assign(n - 1, 0.0);
  mass_.assign(n, 1.0);
  length_.assign(n, 1.0);
  inertia_.resize(n);
  for (std::size_t i = 0; i < n; ++i) inertia_[i] = mass_[i] * length_[i] * length_[i] / 12.0;
  totalMass_ = 0.0;
  for (double m : mass_) totalMass_ += m;
  // w(i, j): weight of joint-acceleration term j in the centre acceleration of segment i.
  const auto w = [](std::size_t i, std::size_t j) { return j < i ? 1.0 : (j == i ? 0.5 : 0.0); };
  std::vector<double> meanWeight(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < n; ++k) meanWeight[j] += mass_[k] * w(k, j);
    meanWeight[j] /= totalMass_;
  }
  massWeight_.assign(n, 0.0);
  couple_.setZero(n_, n_);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < n; ++k) {
      massWeight_[i] += w(i, k) * mass_[k];
      for (std::size_t j = 0; j < n; ++j) {
        couple_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) +=
            w(i, k) * mass_[k] * (w(k, j) - meanWeight[j]);
      }
    }
  }
  double largest = 0.0, asymmetry = 0.0;
  for (Eigen::Index i = 0; i < n_; ++i) {
    for (Eigen::Index j = 0; j < n_; ++j) {
      largest = std::max(largest, std::fabs(couple_(i, j)));
      asymmetry = std::max(asymmetry, std::fabs(couple_(i, j) - couple_(j, i)));
    }
  }
  fixedSizeKernel_ = n_ <= kSwimmerFixedMaxSegments && asymmetry <= 1e-12 * largest;
  if (fixedSizeKernel_) {
    body_.segments = n_;
    body_.inverseTotalMass = 1.0 / totalMass_;
    for (std::size_t i = 0; i < n; ++i) {
      body_.mass[i] = mass_[i];
      body_.length[i] = length_[i];
      body_.inertia[i] = inertia_[i];
      body_.massWeight[i] = massWeight_[i];
      body_.dragFactor[i] = -config_.viscosity * length_[i];
      body_.viscousMoment[i] = -config_.viscosity * length_[i] * length_[i] * length_[i] / 12.0;
      for (std::size_t j = 0; j < n; ++j) {
        const double g = couple_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
        const std::size_t at = i * SwimmerBody::kMax + j;
        body_.matrixCoupling[at] = -length_[i] * length_[j] * g;
        body_.centripetalCoupling[at] = g * length_[j];
      }
    }
  }
  system_.setZero(n_, n_);
  rhs_.setZero(n_);
  solution_.setZero(n_);
  lu_ = Eigen::PartialPivLU<Eigen::MatrixXd>(n_);
  for (auto* v : {&cos_, &sin_, &force_x_, &force_y_}) v->assign(n, 0.0);
  for (auto* v : {&k1_, &k2_, &k3_, &k4_, &tmp_}) v->assign(2 * n + 2, 0.0);
}

std::vector<std::uint64_t> Swimmer::snapshot() const {
  return stateAndStepsSnapshot(name(), state_, steps_);
}

void Swimmer::restore(std::span<const std::uint64_t> words) {
  restoreStateAndSteps(name(), words, state_, steps_);
}

std::vector<StateRange> Swimmer::typicalStateRanges() const {
  // Angles are wrapped into [-pi, pi]; velocities: seen under random torques (|u| <= 5).
  constexpr double pi = std::numbers::pi;
  std::vector<StateRange> ranges{{-1.0, 1.0}, {-1.0, 1.0}};
  for (int i = 0; i < n_; ++i) {
    ranges.push_back({-pi, pi});
    ranges.push_back({-5.0, 5.0});
  }
  return ranges;
}

ActionSpace Swimmer::actionSpace() const {
  ActionSpace space;
  space.components = static_cast<std::size_t>(n_ - 1);
  space.low.assign(space.components, -config_.maxTorque);
  space.high.assign(space.components, config_.maxTorque);
  for (int j = 1; j < n_; ++j) space.names.push_back(fmt::format("u{}", j));
  return space;
}

void Swimmer::reset(Rng& rng) {
  std::fill(state_.begin(), state_.end(), 0.0);
  for (int i = 0; i < n_; ++i) {
    state_[static_cast<std::size_t>(2 + 2 * i)] =
        rng.uniform(-config_.startAngleNoise, config_.startAngleNoise);
  }
  steps_ = 0;
}

void Swimmer::setState(std::span<const double> state) {
  if (state.size() != state_.size()) {
    throw InputError(fmt::format("swimmer with {} segments takes {} state variables, got {}", n_,
                                 state_.size(), state.size()),
                     "swimmer state");
  }
  for (double v : state) {
    if (!std::isfinite(v)) throw InputError("swimmer state must be finite", "swimmer state");
  }
  std::copy(state.begin(), state.end(), state_.begin());
  steps_ = 0;
}

void Swimmer::derivative(std::span<const double> s, std::span<const double> torque,
                         std::span<double> out) {
  if (fixedSize()) {
    swimmerFixedDerivative(body_, s.data(), torque.data(), out.data());
  } else {
    derivativeReference(s, torque, out);
  }
}

void Swimmer::derivativeReference(std::span<const double> s, std::span<const double> torque,
                                  std::span<double> out) {
  const auto n = static_cast<std::size_t>(n_);
  const double k = config_.viscosity;
  for (std::size_t i = 0; i < n; ++i) {
    cos_[i] = expr::trig::cos(s[2 + 2 * i]);
    sin_[i] = expr::trig::sin(s[2 + 2 * i]);
  }
  // Centre velocities G'_i relative to A'_0 = 0, then shifted so that sum m_i G'_i / M = G'.
  double ax = 0.0, ay = 0.0, meanX = 0.0, meanY = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double rate = length_[i] * s[3 + 2 * i];
    const double nextX = ax - rate * sin_[i], nextY = ay + rate * cos_[i];
    force_x_[i] = 0.5 * (ax + nextX);  // G'_i for now; turned into the drag force below.
    force_y_[i] = 0.5 * (ay + nextY);
    meanX += mass_[i] * force_x_[i];
    meanY += mass_[i] * force_y_[i];
    ax = nextX;
    ay = nextY;
  }
  const double shiftX = s[0] - meanX / totalMass_, shiftY = s[1] - meanY / totalMass_;
  // Normal drag F_i = -k l_i (G'_i . n_i) n_i, n_i = (-sin, cos).
  double sumFx = 0.0, sumFy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double vx = force_x_[i] + shiftX, vy = force_y_[i] + shiftY;
    const double normal = -k * length_[i] * (-vx * sin_[i] + vy * cos_[i]);
    force_x_[i] = -normal * sin_[i];
    force_y_[i] = normal * cos_[i];
    sumFx += force_x_[i];
    sumFy += force_y_[i];
  }
  // Translation: M G'' = sum F_i (the free tail, f_n = 0).
  const double gxx = sumFx / totalMass_, gyy = sumFy / totalMass_;
  // Rotation rows, with G'' substituted: see the derivation in docs/environments.md.
  double prefixX = 0.0, prefixY = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    const double li = length_[i], ci = cos_[i], si = sin_[i];
    const double halfX = prefixX + 0.5 * force_x_[i], halfY = prefixY + 0.5 * force_y_[i];
    prefixX += force_x_[i];
    prefixY += force_y_[i];
    const double dth = s[3 + 2 * i];
    double rhs = -k * dth * li * li * li / 12.0;
    if (i > 0) rhs += torque[i - 1];
    if (i + 1 < n) rhs -= torque[i];
    rhs += li * massWeight_[i] * (ci * gyy - si * gxx);
    rhs -= li * (ci * halfY - si * halfX);
    double centripetal = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      const double lj = length_[j], dthj = s[3 + 2 * j];
      const double g = couple_(ii, jj);
      centripetal += g * lj * dthj * dthj * (ci * sin_[j] - si * cos_[j]);
      system_(ii, jj) = -li * lj * g * (ci * cos_[j] + si * sin_[j]);
    }
    system_(ii, ii) += inertia_[i];
    rhs -= li * centripetal;
    rhs_(ii) = rhs;
  }
  lu_.compute(system_);
  solution_.noalias() = lu_.solve(rhs_);
  out[0] = gxx;
  out[1] = gyy;
  for (std::size_t i = 0; i < n; ++i) {
    out[2 + 2 * i] = s[3 + 2 * i];
    out[3 + 2 * i] = solution_(static_cast<Eigen::Index>(i));
  }
}

void Swimmer::integrateReference(double h) {
  const std::size_t dim = state_.size();
  if (config_.integrator == Integrator::Euler) {
    derivativeReference(state_, torque_, k1_);
    for (std::size_t i = 0; i < dim; ++i) state_[i] += h * k1_[i];
  } else {
    const double half = h / 2.0;
    derivativeReference(state_, torque_, k1_);
    for (std::size_t i = 0; i < dim; ++i) tmp_[i] = state_[i] + half * k1_[i];
    derivativeReference(tmp_, torque_, k2_);
    for (std::size_t i = 0; i < dim; ++i) tmp_[i] = state_[i] + half * k2_[i];
    derivativeReference(tmp_, torque_, k3_);
    for (std::size_t i = 0; i < dim; ++i) tmp_[i] = state_[i] + h * k3_[i];
    derivativeReference(tmp_, torque_, k4_);
    const double sixth = h / 6.0;
    for (std::size_t i = 0; i < dim; ++i) {
      state_[i] += sixth * (k1_[i] + 2.0 * k2_[i] + 2.0 * k3_[i] + k4_[i]);
    }
  }
  for (int i = 0; i < n_; ++i) {
    double& th = state_[static_cast<std::size_t>(2 + 2 * i)];
    th = wrapAngle(th);
  }
}

StepResult Swimmer::step(std::span<const double> action) {
  if (action.size() != torque_.size()) {
    throw InputError(fmt::format("swimmer with {} segments takes {} action components, got {}", n_,
                                 torque_.size(), action.size()),
                     "swimmer action");
  }
  for (std::size_t j = 0; j < torque_.size(); ++j) {
    torque_[j] =
        std::isnan(action[j]) ? 0.0 : std::clamp(action[j], -config_.maxTorque, config_.maxTorque);
  }
  const double h = config_.dt / config_.substeps;
  if (fixedSize()) {
    swimmerFixedIntegrate(body_, config_.integrator, h, config_.substeps, state_.data(),
                          torque_.data());
  } else {
    for (int i = 0; i < config_.substeps; ++i) integrateReference(h);
  }
  ++steps_;
  StepResult result;
  result.reward = state_[0] * config_.dt;
  result.truncated = config_.horizon > 0 && steps_ >= config_.horizon;
  return result;
}

}  // namespace gpfd::env
