#include "gpfd/env/cartpole.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "batch_factories.hpp"
#include "cartpole_dynamics.hpp"
#include "gpfd/env/common_params.hpp"
#include "gpfd/env/snapshot.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

const ParamTable<CartPoleConfig>& CartPoleConfig::table() {
  static const auto table = [] {
    ParamTable<CartPoleConfig> t("cartpole");
    t.real(
        "gravity", [](auto& c) -> auto& { return c.gravity; }, 0.0, 100.0,
        "gravitational acceleration in m/s^2 (CLSquare: 9.81)");
    // The pole's time scale is sqrt(l / g) ~ 0.2 s: longer steps no longer follow it.
    declareIntegration(
        t, "euler: Gymnasium's, every right-hand side from the old state; rk4",
        "integration steps per control interval (CLSquare: rk4 with 10)",
        [](const CartPoleConfig&) { return 0.05; }, "at most 0.05 s (Gymnasium's: 0.02 s)");
    t.real(
        "max_force", [](auto& c) -> auto& { return c.maxForce; }, 1e-3, 1000.0,
        "force bound (continuous) or magnitude (discrete), N");
    declareActionKind(t,
                      "continuous: F in [-max_force, max_force], clipped; discrete: 0, 1 = "
                      "-max_force, +max_force");
    declareTimeLimit(
        t, "max_steps", [](auto& c) -> auto& { return c.maxSteps; }, "steps");
    return t;
  }();
  return table;
}

EnvInfo CartPole::info() {
  EnvInfo info{"cartpole", "pole balancing on a cart (Barto et al. 1983; Gymnasium CartPole-v1)",
               CartPoleConfig::table().specs(), [](const Params& p) {
                 return std::make_unique<CartPole>(CartPoleConfig::fromParams(p));
               }};
  info.batch = batch::formOf(&batch::makeCartPole);
  return info;
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
    space.choices = {2};
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

std::vector<std::uint64_t> CartPole::snapshot() const {
  return stateAndStepsSnapshot(name(), state_, steps_);
}

void CartPole::restore(std::span<const std::uint64_t> words) {
  restoreStateAndSteps(name(), words, state_, steps_);
}

std::vector<StateRange> CartPole::typicalStateRanges() const {
  // x and th: the failure limits; dx and dth: seen within episodes under random forces.
  using cartpole::kThetaThreshold, cartpole::kXThreshold;
  return {
      {-kXThreshold, kXThreshold}, {-3.0, 3.0}, {-kThetaThreshold, kThetaThreshold}, {-3.5, 3.5}};
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
