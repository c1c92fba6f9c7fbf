#include "gpfd/env/acrobot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "gpfd/env/angles.hpp"
#include "gpfd/env/params.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

// Constants of BENCHMARKS.md (Gymnasium Acrobot-v1).
constexpr double kM1 = 1.0, kM2 = 1.0, kL1 = 1.0, kLc1 = 0.5, kLc2 = 0.5, kI1 = 1.0, kI2 = 1.0;
constexpr double kG = 9.8;
constexpr double kPi = std::numbers::pi;
constexpr double kMaxVel1 = 4 * kPi, kMaxVel2 = 9 * kPi;

}  // namespace

AcrobotConfig AcrobotConfig::fromParams(const Params& params) {
  const ParamReader in("acrobot", params);
  AcrobotConfig c;
  c.dynamics =
      in.choice("dynamics", "book", {"book", "nips"}) == "nips" ? Dynamics::Nips : Dynamics::Book;
  c.integrator = integratorFromName(in.choice("integrator", "rk4", {"rk4", "euler"}));
  c.dt = in.positive("dt", c.dt);
  c.substeps = in.integer("substeps", c.substeps, 1, 1000000);
  c.maxTorque = in.positive("max_torque", c.maxTorque);
  c.discrete = in.choice("actions", "continuous", {"continuous", "discrete"}) == "discrete";
  c.maxSteps = in.integer("max_steps", c.maxSteps, 0, 1000000000);
  return c;
}

Params AcrobotConfig::toParams() const {
  return {{"dynamics", dynamics == Dynamics::Nips ? "nips" : "book"},
          {"integrator", integratorName(integrator)},
          {"dt", numberText(dt)},
          {"substeps", std::to_string(substeps)},
          {"max_torque", numberText(maxTorque)},
          {"actions", discrete ? "discrete" : "continuous"},
          {"max_steps", std::to_string(maxSteps)}};
}

std::vector<ParamSpec> AcrobotConfig::paramSpecs() {
  const AcrobotConfig d;
  return {
      {"dynamics", "book", "book (Sutton & Barto) | nips (without the dth1^2 term in ddth2)"},
      {"integrator", "rk4", "rk4 (Gymnasium) | euler (Sutton & Barto: use with dt=0.2 substeps=4)"},
      {"dt", numberText(d.dt), "control interval in seconds; the torque is held over it"},
      {"substeps", std::to_string(d.substeps),
       "integration steps per control interval; angles wrapped and velocities clipped after each"},
      {"max_torque", numberText(d.maxTorque), "torque bound (continuous) or magnitude (discrete)"},
      {"actions", "continuous",
       "continuous (tau in [-max_torque, max_torque], clipped) | discrete (0,1,2 = -1,0,+1 x "
       "max_torque)"},
      {"max_steps", std::to_string(d.maxSteps), "time limit in steps (truncation); 0 = none"},
  };
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
