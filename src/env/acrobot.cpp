#include "gpfd/env/acrobot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gpfd/env/angles.hpp"
#include "gpfd/env/common_params.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

// Constants of Gymnasium's Acrobot-v1 (docs/benchmarks.md).
constexpr double kM1 = 1.0, kM2 = 1.0, kL1 = 1.0, kLc1 = 0.5, kLc2 = 0.5, kI1 = 1.0, kI2 = 1.0;
constexpr double kG = 9.8;
constexpr double kPi = std::numbers::pi;
constexpr double kMaxVel1 = 4 * kPi, kMaxVel2 = 9 * kPi;

}  // namespace

const ParamTable<AcrobotConfig>& AcrobotConfig::table() {
  using Dynamics = AcrobotConfig::Dynamics;
  static const auto table = [] {
    ParamTable<AcrobotConfig> t("acrobot");
    t.choice(
        "dynamics", [](auto& c) -> auto& { return c.dynamics; },
        std::vector<std::pair<std::string, Dynamics>>{{"book", Dynamics::Book},
                                                      {"nips", Dynamics::Nips}},
        "book: Sutton & Barto's equations; nips: without the dth1^2 term in ddth2");
    // Beyond these steps the velocities reach their clipping bounds within a step.
    declareIntegration(
        t, "rk4: Gymnasium's; euler: Sutton & Barto's, with dt=0.2 substeps=4",
        "integration steps per control interval; angles wrapped and velocities clipped after each",
        [](const AcrobotConfig& c) { return c.integrator == Integrator::Rk4 ? 0.2 : 0.05; },
        "at most 0.2 s with rk4 (Gymnasium's step) and 0.05 s with euler (Sutton & Barto's)");
    t.real(
        "max_torque", [](auto& c) -> auto& { return c.maxTorque; }, 1e-3, 100.0,
        "torque bound (continuous) or magnitude (discrete)");
    declareActionKind(t,
                      "continuous: tau in [-max_torque, max_torque], clipped; discrete: 0, 1, 2 "
                      "= -1, 0, +1 x max_torque");
    declareTimeLimit(
        t, "max_steps", [](auto& c) -> auto& { return c.maxSteps; }, "steps");
    return t;
  }();
  return table;
}

EnvInfo Acrobot::info() {
  return {"acrobot",
          "two-link underactuated pendulum; swing the tip above the bar (Sutton & Barto; "
          "Gymnasium Acrobot-v1)",
          AcrobotConfig::table().specs(),
          [](const Params& p) { return std::make_unique<Acrobot>(AcrobotConfig::fromParams(p)); }};
}

Acrobot::Acrobot(AcrobotConfig config) : config_(config) {}

const std::vector<std::string>& Acrobot::stateNames() const {
  static const std::vector<std::string> names{"th1", "th2", "dth1", "dth2"};
  return names;
}

ActionSpace Acrobot::actionSpace() const {
  ActionSpace space;
  space.names = {"torque"};
  if (config_.discrete) {
    space.kind = ActionSpace::Kind::Discrete;
    space.choices = 3;
  } else {
    space.low = {-config_.maxTorque};
    space.high = {config_.maxTorque};
  }
  return space;
}

void Acrobot::reset(Rng& rng) {
  for (double& v : state_) v = rng.uniform(-0.1, 0.1);
  steps_ = 0;
}

void Acrobot::setState(std::span<const double> state) {
  if (state.size() != 4) {
    throw InputError(fmt::format("acrobot takes 4 state variables, got {}", state.size()),
                     "acrobot state");
  }
  for (double v : state) {
    if (!std::isfinite(v)) throw InputError("acrobot state must be finite", "acrobot state");
  }
  std::copy(state.begin(), state.end(), state_.begin());
  steps_ = 0;
}

Acrobot::State Acrobot::derivative(const State& s, double tau) const {
  const double th1 = s[0], th2 = s[1], dth1 = s[2], dth2 = s[3];
  const double sin2 = std::sin(th2), cos2 = std::cos(th2);
  const double d1 =
      kM1 * kLc1 * kLc1 + kM2 * (kL1 * kL1 + kLc2 * kLc2 + 2 * kL1 * kLc2 * cos2) + kI1 + kI2;
  const double d2 = kM2 * (kLc2 * kLc2 + kL1 * kLc2 * cos2) + kI2;
  const double phi2 = kM2 * kLc2 * kG * std::cos(th1 + th2 - kPi / 2.0);
  const double phi1 = -kM2 * kL1 * kLc2 * (dth2 * dth2) * sin2 -
                      2 * kM2 * kL1 * kLc2 * dth2 * dth1 * sin2 +
                      (kM1 * kLc1 + kM2 * kL1) * kG * std::cos(th1 - kPi / 2.0) + phi2;
  double numerator = tau + d2 / d1 * phi1;
  if (config_.dynamics == AcrobotConfig::Dynamics::Book) {
    numerator -= kM2 * kL1 * kLc2 * (dth1 * dth1) * sin2;
  }
  numerator -= phi2;
  const double ddth2 = numerator / (kM2 * kLc2 * kLc2 + kI2 - d2 * d2 / d1);
  const double ddth1 = -(d2 * ddth2 + phi1) / d1;
  return {dth1, dth2, ddth1, ddth2};
}

std::vector<StateRange> Acrobot::typicalStateRanges() const {
  // Exact: the angles are wrapped, the velocities clipped (Gymnasium's bounds).
  return {{-kPi, kPi}, {-kPi, kPi}, {-kMaxVel1, kMaxVel1}, {-kMaxVel2, kMaxVel2}};
}

bool Acrobot::terminal() const {
  return -std::cos(state_[0]) - std::cos(state_[1] + state_[0]) > 1.0;
}

double Acrobot::torqueOf(std::span<const double> action) const {
  if (action.size() != 1) {
    throw InputError(fmt::format("acrobot takes 1 action component, got {}", action.size()),
                     "acrobot action");
  }
  const double a = action[0];
  if (config_.discrete) {
    if (!(a == 0.0 || a == 1.0 || a == 2.0)) {
      throw InputError(fmt::format("acrobot discrete action must be 0, 1 or 2, got {}", a),
                       "acrobot action");
    }
    return (a - 1.0) * config_.maxTorque;
  }
  if (std::isnan(a)) return 0.0;
  return std::clamp(a, -config_.maxTorque, config_.maxTorque);
}

StepResult Acrobot::step(std::span<const double> action) {
  const double tau = torqueOf(action);
  const double h = config_.dt / config_.substeps;
  const auto f = [&](const State& s) { return derivative(s, tau); };
  for (int i = 0; i < config_.substeps; ++i) {
    state_ = integrateStep<4>(config_.integrator, state_, h, f);
    state_[0] = wrapAngle(state_[0]);
    state_[1] = wrapAngle(state_[1]);
    state_[2] = std::clamp(state_[2], -kMaxVel1, kMaxVel1);
    state_[3] = std::clamp(state_[3], -kMaxVel2, kMaxVel2);
  }
  ++steps_;
  StepResult result;
  result.terminated = terminal();
  result.reward = result.terminated ? 0.0 : -1.0;
  result.truncated = config_.maxSteps > 0 && steps_ >= config_.maxSteps;
  return result;
}

}  // namespace gpfd::env
