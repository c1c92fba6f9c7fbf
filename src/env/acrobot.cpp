#include "gpfd/env/acrobot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "acrobot_dynamics.hpp"
#include "batch_factories.hpp"
#include "gpfd/env/angles.hpp"
#include "gpfd/env/common_params.hpp"
#include "gpfd/env/snapshot.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

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
  EnvInfo info{"acrobot",
               "two-link underactuated pendulum; swing the tip above the bar (Sutton & Barto; "
               "Gymnasium Acrobot-v1)",
               AcrobotConfig::table().specs(), [](const Params& p) {
                 return std::make_unique<Acrobot>(AcrobotConfig::fromParams(p));
               }};
  info.batch = batch::formOf(&batch::makeAcrobot);
  return info;
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
    space.choices = {3};
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

std::vector<std::uint64_t> Acrobot::snapshot() const {
  return stateAndStepsSnapshot(name(), state_, steps_);
}

void Acrobot::restore(std::span<const std::uint64_t> words) {
  restoreStateAndSteps(name(), words, state_, steps_);
}

std::vector<StateRange> Acrobot::typicalStateRanges() const {
  // Exact: the angles are wrapped, the velocities clipped (Gymnasium's bounds).
  using namespace acrobot;
  return {{-kPi, kPi}, {-kPi, kPi}, {-kMaxVel1, kMaxVel1}, {-kMaxVel2, kMaxVel2}};
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
