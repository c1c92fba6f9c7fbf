// The mountain car (Moore 1990; Sutton & Barto, Reinforcement Learning: An Introduction, 2nd ed.
// 2018, section 10.1) as a gpfd plug-in, with a continuous throttle: an underpowered car in a
// valley must rock back and forth to reach the hill-top on the right.
//
//   v' = clip(v + power * a - 0.0025 cos(3 x), -0.07, 0.07)
//   x' = clip(x + v', -1.2, 0.5); at the left wall (x' = -1.2) the car stops: v' = 0
//
// a in [-1, 1] (Sutton & Barto's three actions are a in {-1, 0, 1}, power 0.001; Gymnasium's
// MountainCar-v0 has the same constants). Reward -1 per step (both); terminal at x' >= 0.5; a
// time limit in steps, 200 by default (MountainCar-v0's TimeLimit). Two start distributions
// (parameter `start`):
//   valley:   x ~ U(-0.6, -0.4), v = 0, as Sutton & Barto and MountainCar-v0;
//   anywhere: x ~ U(-1.2, 0.5), v ~ U(-0.07, 0.07), uniform over the state space: exploring starts
//             (Sutton & Barto, section 5.3), the default.
// From the valley, a policy whose exploration is independent noise on each step's throttle does
// not reach the goal in 200 steps, so every return is -200 and policy gradient has nothing to
// follow (README.md: 20 trainings of 100 updates of 50 episodes, all -200 throughout). Started
// anywhere, some episodes reach the goal at once, and the learner improves from there.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/run/plugin.hpp"
#include "gpfd/util/error.hpp"

namespace {

using namespace gpfd;

constexpr double kMinX = -1.2, kMaxX = 0.5, kGoalX = 0.5, kMaxSpeed = 0.07, kGravity = 0.0025;

enum class Start { Valley, Anywhere };

struct MountainCarConfig {
  double power = 0.001;  // Acceleration per unit of throttle (Sutton & Barto; Gymnasium: 0.0015).
  int maxSteps = 200;    // Time limit in steps (truncation); 0 = none. Gymnasium: 200.
  Start start = Start::Anywhere;

  static const ParamTable<MountainCarConfig>& table() {
    static const auto table =
        ParamTable<MountainCarConfig>("mountain-car")
            .real(
                "power", [](auto& c) -> auto& { return c.power; }, 1e-4, 0.01,
                "acceleration per unit of throttle (Sutton & Barto: 0.001; Gymnasium: 0.0015)")
            .integer(
                "max_steps", [](auto& c) -> auto& { return c.maxSteps; }, 0, 1000000000,
                "time limit in steps (truncation; Gymnasium's MountainCar-v0: 200); 0 = none")
            .choice(
                "start", [](auto& c) -> auto& { return c.start; },
                std::vector<std::pair<std::string, Start>>{{"valley", Start::Valley},
                                                           {"anywhere", Start::Anywhere}},
                "valley: x ~ U(-0.6, -0.4), v = 0 (Sutton & Barto); anywhere: uniform over the "
                "state space (exploring starts)");
    return table;
  }
};

class MountainCar final : public env::Environment {
 public:
  explicit MountainCar(MountainCarConfig config) : config_(config) {}

  static env::EnvInfo info() {
    return {"mountain-car",
            "drive an underpowered car up a hill by rocking it (Moore 1990; Sutton & Barto "
            "2018, section 10.1), continuous throttle; a plug-in (examples/mountain-car)",
            MountainCarConfig::table().specs(), [](const env::Params& p) {
              return std::make_unique<MountainCar>(MountainCarConfig::table().read(p));
            }};
  }

  std::string name() const override { return "mountain-car"; }
  env::Params params() const override { return MountainCarConfig::table().write(config_); }
  const std::vector<std::string>& stateNames() const override {
    static const std::vector<std::string> names{"x", "v"};
    return names;
  }
  env::ActionSpace actionSpace() const override {
    env::ActionSpace space;
    space.low = {-1.0};
    space.high = {1.0};
    space.names = {"throttle"};
    return space;
  }
  void reset(Rng& rng) override {
    if (config_.start == Start::Valley) {
      state_ = {rng.uniform(-0.6, -0.4), 0.0};
    } else {
      // Below the goal: lo + (hi - lo) * u can round up to hi.
      const double x = std::min(rng.uniform(kMinX, kGoalX), std::nextafter(kGoalX, kMinX));
      state_ = {x, rng.uniform(-kMaxSpeed, kMaxSpeed)};
    }
    steps_ = 0;
  }
  std::span<const double> state() const override { return state_; }
  void setState(std::span<const double> state) override {
    if (state.size() != 2 || !(state[0] >= kMinX && state[0] <= kMaxX) ||
        !(std::fabs(state[1]) <= kMaxSpeed)) {
      throw InputError("mountain-car takes x in [-1.2, 0.5] and v in [-0.07, 0.07]",
                       "mountain-car state");
    }
    state_ = {state[0], state[1]};
    steps_ = 0;
  }
  env::StepResult step(std::span<const double> action) override {
    if (action.size() != 1) {
      throw InputError("mountain-car takes 1 action component", "mountain-car action");
    }
    const double a = std::isnan(action[0]) ? 0.0 : std::clamp(action[0], -1.0, 1.0);
    double v = state_[1] + config_.power * a - kGravity * std::cos(3.0 * state_[0]);
    v = std::clamp(v, -kMaxSpeed, kMaxSpeed);
    double x = std::clamp(state_[0] + v, kMinX, kMaxX);
    if (x == kMinX) v = 0.0;
    state_ = {x, v};
    ++steps_;
    env::StepResult result;
    result.terminated = x >= kGoalX;
    result.reward = -1.0;
    result.truncated = config_.maxSteps > 0 && steps_ >= config_.maxSteps;
    return result;
  }
  // Exact: the dynamics clip both variables.
  std::vector<env::StateRange> typicalStateRanges() const override {
    return {{kMinX, kMaxX}, {-kMaxSpeed, kMaxSpeed}};
  }

 private:
  MountainCarConfig config_;
  std::array<double, 2> state_{-0.5, 0.0};
  int steps_ = 0;
};

void registerMountainCar(PluginRegistries& registries) {
  registries.environments.add(MountainCar::info());
}

}  // namespace

GPFD_PLUGIN(registerMountainCar)
