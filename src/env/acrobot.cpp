#include "gpfd/env/acrobot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "acrobot_dynamics.hpp"
#include "gpfd/env/params.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

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
  return acrobot::derivative(config_.dynamics, s, tau);
}

bool Acrobot::terminal() const { return acrobot::terminal(state_); }

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
  }
  return acrobot::torque(config_, a);
}

StepResult Acrobot::step(std::span<const double> action) {
  acrobot::advance(config_, state_, torqueOf(action));
  ++steps_;
  StepResult result;
  result.terminated = terminal();
  result.reward = result.terminated ? 0.0 : -1.0;
  result.truncated = config_.maxSteps > 0 && steps_ >= config_.maxSteps;
  return result;
}

}  // namespace gpfd::env
