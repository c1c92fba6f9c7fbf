#include "gpfd/env/cartpole.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "cartpole_dynamics.hpp"
#include "gpfd/env/params.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

CartPoleConfig CartPoleConfig::fromParams(const Params& params) {
  const ParamReader in("cartpole", params);
  CartPoleConfig c;
  c.gravity = in.real("gravity", c.gravity, -1e6, 1e6);
  c.integrator = integratorFromName(in.choice("integrator", "euler", {"euler", "rk4"}));
  c.dt = in.positive("dt", c.dt);
  c.substeps = in.integer("substeps", c.substeps, 1, 1000000);
  c.maxForce = in.positive("max_force", c.maxForce);
  c.discrete = in.choice("actions", "continuous", {"continuous", "discrete"}) == "discrete";
  c.maxSteps = in.integer("max_steps", c.maxSteps, 0, 1000000000);
  return c;
}

Params CartPoleConfig::toParams() const {
  return {{"gravity", numberText(gravity)},
          {"integrator", integratorName(integrator)},
          {"dt", numberText(dt)},
          {"substeps", std::to_string(substeps)},
          {"max_force", numberText(maxForce)},
          {"actions", discrete ? "discrete" : "continuous"},
          {"max_steps", std::to_string(maxSteps)}};
}

std::vector<ParamSpec> CartPoleConfig::paramSpecs() {
  const CartPoleConfig d;
  return {
      {"gravity", numberText(d.gravity), "gravitational acceleration in m/s^2 (CLSquare: 9.81)"},
      {"integrator", "euler", "euler (Gymnasium, all right-hand sides from the old state) | rk4"},
      {"dt", numberText(d.dt), "control interval in seconds; the force is held over it"},
      {"substeps", std::to_string(d.substeps),
       "integration steps per control interval (CLSquare: rk4 with 10)"},
      {"max_force", numberText(d.maxForce), "force bound (continuous) or magnitude (discrete), N"},
      {"actions", "continuous",
       "continuous (F in [-max_force, max_force], clipped) | discrete (0,1 = "
       "-max_force,+max_force)"},
      {"max_steps", std::to_string(d.maxSteps), "time limit in steps (truncation); 0 = none"},
  };
}

CartPole::CartPole(CartPoleConfig config) : config_(config) {}

const std::vector<std::string>& CartPole::stateNames() const {
  static const std::vector<std::string> names{"x", "dx", "th", "dth"};
  return names;
}

ActionSpace CartPole::actionSpace() const {
  ActionSpace space;
  space.names = {"force"};
  if (config_.discrete) {
    space.kind = ActionSpace::Kind::Discrete;
    space.choices = 2;
  } else {
    space.low = {-config_.maxForce};
    space.high = {config_.maxForce};
  }
  return space;
}

void CartPole::reset(Rng& rng) {
  for (double& v : state_) v = rng.uniform(-0.05, 0.05);
  steps_ = 0;
}

void CartPole::setState(std::span<const double> state) {
  if (state.size() != 4) {
    throw InputError(fmt::format("cartpole takes 4 state variables, got {}", state.size()),
                     "cartpole state");
  }
  for (double v : state) {
    if (!std::isfinite(v)) throw InputError("cartpole state must be finite", "cartpole state");
  }
  std::copy(state.begin(), state.end(), state_.begin());
  steps_ = 0;
}

CartPole::State CartPole::derivative(const State& s, double force) const {
  return cartpole::derivative(config_.gravity, s, force);
}

bool CartPole::terminal() const { return cartpole::terminal(state_); }

double CartPole::forceOf(std::span<const double> action) const {
  if (action.size() != 1) {
    throw InputError(fmt::format("cartpole takes 1 action component, got {}", action.size()),
                     "cartpole action");
  }
  const double a = action[0];
  if (config_.discrete) {
    if (!(a == 0.0 || a == 1.0)) {
      throw InputError(fmt::format("cartpole discrete action must be 0 or 1, got {}", a),
                       "cartpole action");
    }
  }
  return cartpole::force(config_, a);
}

StepResult CartPole::step(std::span<const double> action) {
  cartpole::advance(config_, state_, forceOf(action));
  ++steps_;
  StepResult result;
  result.terminated = terminal();
  result.reward = 1.0;
  result.truncated = config_.maxSteps > 0 && steps_ >= config_.maxSteps;
  return result;
}

}  // namespace gpfd::env
