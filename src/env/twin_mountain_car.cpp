// env: the twins of Gymnasium's MountainCar-v0 (gymnasium/envs/classic_control/mountain_car.py)
// and MountainCarContinuous-v0 (continuous_mountain_car.py), the same in Gymnasium 1.1 to 1.4.
// MountainCar-v0 computes in float64 throughout. MountainCarContinuous-v0 stores its state as
// float32 after each step (a float64 one after the reset), and its force is the action's type, so
// its arithmetic follows NumPy's promotion.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "gpfd/util/error.hpp"
#include "lane_copies.hpp"
#include "twin_params.hpp"
#include "twins.hpp"

namespace gpfd::env::twin {
namespace {

constexpr double kMinPosition = -1.2, kMaxPosition = 0.6, kMaxSpeed = 0.07;

template <int DefaultSteps>
struct MountainCarConfig {
  TwinSettings settings{Promotion::Nep50, DefaultSteps};
  double goalVelocity = 0.0;

  static const ParamTable<MountainCarConfig>& table() {
    static const auto table = [] {
      ParamTable<MountainCarConfig> t(DefaultSteps == 200 ? "MountainCar-v0"
                                                          : "MountainCarContinuous-v0");
      declareTwinSettings(t);
      t.real(
          "goal_velocity", [](auto& c) -> auto& { return c.goalVelocity; }, -1.0, 1.0,
          "Gymnasium's keyword: the least velocity at the goal that ends the episode");
      return t;
    }();
    return table;
  }
};
using DiscreteConfig = MountainCarConfig<200>;
using ContinuousConfig = MountainCarConfig<999>;

// What both share: the start state (position uniform in [-0.6, -0.4], velocity 0), the state
// variables (position, velocity) and their setting.
class MountainCarBase : public GymnasiumTwin {
 protected:
  using GymnasiumTwin::GymnasiumTwin;
  void setState(std::span<const double> state) override {
    if (state.size() != 2) throw InputError(name() + " takes 2 state variables", "state");
    dynamics_.assign(state.begin(), state.end());
    extra_ = 1;  // Set as a float64 state, as after a reset.
    observe();
    roundObservation();
  }
  void start(numpy::Pcg64& random) override {
    dynamics_ = {random.uniform(-0.6, -0.4), 0.0};
    extra_ = 1;  // The state is a float64 array until the first step.
    observe();
  }
  void observe() {
    for (std::size_t i = 0; i < 2; ++i) observation_[i] = dynamics_[i];
  }
};

class MountainCarTwin final : public MountainCarBase {
 public:
  explicit MountainCarTwin(const DiscreteConfig& config)
      : MountainCarBase("MountainCar-v0", 2, config.settings), config_(config) {
    dynamics_.assign(2, 0.0);
  }
  Params params() const override { return DiscreteConfig::table().write(config_); }
  ActionSpace actionSpace() const override { return discreteActions(3); }
  std::unique_ptr<BatchEnvironment> makeLanes(BatchIsa isa) const override {
    return makeLaneCopies(*this, isa);
  }

 private:
  friend class GymnasiumTwin;  // stepFinal calls advance.
  StepResult advance(std::span<const double> action, ActionKind) override {
    checkActionSize(action, 1);
    const double a = action[0];
    if (!(a == 0.0 || a == 1.0 || a == 2.0)) {
      throw InputError(fmt::format("MountainCar-v0's action is 0, 1 or 2 (Discrete(3)), got {}", a),
                       "MountainCar-v0 action");
    }
    constexpr double kForce = 0.001, kGravity = 0.0025;
    double position = dynamics_[0], velocity = dynamics_[1];
    velocity += (a - 1) * kForce + std::cos(3 * position) * (-kGravity);
    velocity = std::isnan(velocity) ? velocity : std::clamp(velocity, -kMaxSpeed, kMaxSpeed);
    position += velocity;
    position = std::isnan(position) ? position : std::clamp(position, kMinPosition, kMaxPosition);
    if (position == kMinPosition && velocity < 0) velocity = 0;
    dynamics_ = {position, velocity};
    observe();
    StepResult result;
    result.terminated = position >= 0.5 && velocity >= config_.goalVelocity;
    result.reward = -1.0;
    return result;
  }

  DiscreteConfig config_;
};

class MountainCarContinuousTwin final : public MountainCarBase {
 public:
  explicit MountainCarContinuousTwin(const ContinuousConfig& config)
      : MountainCarBase("MountainCarContinuous-v0", 2, config.settings), config_(config) {
    dynamics_.assign(2, 0.0);
  }
  Params params() const override { return ContinuousConfig::table().write(config_); }
  ActionSpace actionSpace() const override { return boxAction(-1.0, 1.0, "force"); }
  std::unique_ptr<BatchEnvironment> makeLanes(BatchIsa isa) const override {
    return makeLaneCopies(*this, isa);
  }

 private:
  friend class GymnasiumTwin;  // stepFinal calls advance.
  // As Pendulum-v1's: every call inlined, gpfd's case (float32 actions, NumPy 2) with its types
  // known where it is compiled (the same operations, without a test of the types per operation).
  [[gnu::flatten]] StepResult advance(std::span<const double> action, ActionKind kind) override {
    checkActionSize(action, 1);
    if (kind == Kind::Float32 && promotion() == Promotion::Nep50) {
      return advanceAs(action, Kind::Float32, Promotion::Nep50);
    }
    return advanceAs(action, kind, promotion());
  }

  [[gnu::always_inline]] StepResult advanceAs(std::span<const double> action, ActionKind kind,
                                              Promotion p) {
    // self.state[0] and [1]: float64 after the reset, float32 after a step.
    const Kind stateKind = extra_ != 0 ? Kind::Float64 : Kind::Float32;
    Num position{dynamics_[0], stateKind, p}, velocity{dynamics_[1], stateKind, p};
    const Num a{action[0], kind, p};
    const Num force = numpy_scalar::pyMin(numpy_scalar::pyMax(a, py(-1.0, p)), py(1.0, p));
    const Num three{3, Kind::PyInt, p};
    const Num cosine = py(std::cos((three * position).value), p);  // math.cos: a Python float.
    velocity = velocity + (force * py(0.0015, p) - py(0.0025, p) * cosine);
    if (velocity > py(kMaxSpeed, p)) velocity = py(kMaxSpeed, p);
    if (velocity < py(-kMaxSpeed, p)) velocity = py(-kMaxSpeed, p);
    position = position + velocity;
    if (position > py(kMaxPosition, p)) position = py(kMaxPosition, p);
    if (position < py(kMinPosition, p)) position = py(kMinPosition, p);
    if (position == py(kMinPosition, p) && velocity < Num{0, Kind::PyInt, p}) {
      velocity = {0, Kind::PyInt, p};
    }
    StepResult result;
    result.terminated = position >= py(0.45, p) && velocity >= py(config_.goalVelocity, p);
    // reward = 0 (100 at the goal), less math.pow(action[0], 2) * 0.1: of the action as given.
    result.reward = (result.terminated ? 100.0 : 0.0) - libmSquare(action[0]) * 0.1;
    // np.array([position, velocity], dtype=np.float32)
    dynamics_ = {numpy_scalar::toFloat32(position.value), numpy_scalar::toFloat32(velocity.value)};
    extra_ = 0;
    observe();
    return result;
  }

  ContinuousConfig config_;
};

}  // namespace

EnvInfo mountainCarTwin() {
  return twinInfo<MountainCarTwin, DiscreteConfig>(
      "MountainCar-v0", "Gymnasium's MountainCar-v0, the same episodes bit for bit (native twin)");
}

EnvInfo mountainCarContinuousTwin() {
  return twinInfo<MountainCarContinuousTwin, ContinuousConfig>(
      "MountainCarContinuous-v0",
      "Gymnasium's MountainCarContinuous-v0, the same episodes bit for bit (native twin)");
}

}  // namespace gpfd::env::twin
