// env: the twin of Gymnasium's CartPole-v1 (gymnasium/envs/classic_control/cartpole.py, the same
// in Gymnasium 1.1 to 1.4): every quantity a float64, so NumPy's promotion does not matter.
#include <fmt/format.h>

#include <cmath>

#include "gpfd/util/error.hpp"
#include "lane_copies.hpp"
#include "twin_params.hpp"
#include "twins.hpp"

namespace gpfd::env::twin {
namespace {

struct CartPoleConfig {
  TwinSettings settings{Promotion::Nep50, 500};
  bool suttonBartoReward = false;

  static const ParamTable<CartPoleConfig>& table() {
    static const auto table = [] {
      ParamTable<CartPoleConfig> t("CartPole-v1");
      declareTwinSettings(t);
      t.flag(
          "sutton_barto_reward", [](auto& c) -> auto& { return c.suttonBartoReward; },
          "Gymnasium's keyword: reward 0 per step and -1 at failure instead of 1 per step");
      return t;
    }();
    return table;
  }
};

// CartPoleEnv's constants and their derived values, computed as its __init__ computes them.
constexpr double kGravity = 9.8, kMassCart = 1.0, kMassPole = 0.1;
constexpr double kTotalMass = kMassPole + kMassCart, kLength = 0.5;
constexpr double kPoleMassLength = kMassPole * kLength, kForceMag = 10.0, kTau = 0.02;
constexpr double kThetaThreshold = 12 * 2 * 3.141592653589793 / 360, kXThreshold = 2.4;

class CartPoleTwin final : public GymnasiumTwin {
 public:
  explicit CartPoleTwin(const CartPoleConfig& config)
      : GymnasiumTwin("CartPole-v1", 4, config.settings), config_(config) {
    dynamics_.assign(4, 0.0);
  }
  Params params() const override { return CartPoleConfig::table().write(config_); }
  ActionSpace actionSpace() const override { return discreteActions(2); }
  std::unique_ptr<BatchEnvironment> makeLanes(BatchIsa isa) const override {
    return makeLaneCopies(*this, isa);
  }
  void setState(std::span<const double> state) override {
    if (state.size() != 4) throw InputError("CartPole-v1 takes 4 state variables", "state");
    dynamics_.assign(state.begin(), state.end());
    extra_ = 0;
    observe();
    roundObservation();
  }

 private:
  friend class GymnasiumTwin;  // stepFinal calls advance.
  void start(numpy::Pcg64& random) override {
    for (double& v : dynamics_) v = random.uniform(-0.05, 0.05);  // uniform(size=(4,))
    extra_ = 0;  // steps_beyond_terminated = None (else extra_ - 1).
    observe();
  }

  StepResult advance(std::span<const double> action, ActionKind) override {
    checkActionSize(action, 1);
    if (!(action[0] == 0.0 || action[0] == 1.0)) {
      throw InputError(
          fmt::format("CartPole-v1's action is 0 or 1 (Discrete(2)), got {}", action[0]),
          "CartPole-v1 action");
    }
    double x = dynamics_[0], xDot = dynamics_[1], theta = dynamics_[2], thetaDot = dynamics_[3];
    const double force = action[0] == 1.0 ? kForceMag : -kForceMag;
    const double cosTheta = std::cos(theta), sinTheta = std::sin(theta);
    const double temp = (force + kPoleMassLength * (thetaDot * thetaDot) * sinTheta) / kTotalMass;
    const double thetaAcc =
        (kGravity * sinTheta - cosTheta * temp) /
        (kLength * (4.0 / 3.0 - kMassPole * (cosTheta * cosTheta) / kTotalMass));
    const double xAcc = temp - kPoleMassLength * thetaAcc * cosTheta / kTotalMass;
    x = x + kTau * xDot;  // The "euler" integrator.
    xDot = xDot + kTau * xAcc;
    theta = theta + kTau * thetaDot;
    thetaDot = thetaDot + kTau * thetaAcc;
    dynamics_[0] = x;
    dynamics_[1] = xDot;
    dynamics_[2] = theta;
    dynamics_[3] = thetaDot;
    observe();

    StepResult result;
    result.terminated =
        x < -kXThreshold || x > kXThreshold || theta < -kThetaThreshold || theta > kThetaThreshold;
    const bool sutton = config_.suttonBartoReward;
    if (!result.terminated) {
      result.reward = sutton ? 0.0 : 1.0;
    } else if (extra_ == 0) {  // The pole just fell.
      extra_ = 1;
      result.reward = sutton ? -1.0 : 1.0;
    } else {  // Stepped on after the end: Gymnasium warns and gives nothing (Sutton-Barto: -1).
      ++extra_;
      result.reward = sutton ? -1.0 : 0.0;
    }
    return result;
  }

  void observe() {
    for (std::size_t i = 0; i < 4; ++i) observation_[i] = dynamics_[i];
  }

  CartPoleConfig config_;
};

}  // namespace

EnvInfo cartPoleTwin() {
  return twinInfo<CartPoleTwin, CartPoleConfig>(
      "CartPole-v1", "Gymnasium's CartPole-v1, the same episodes bit for bit (native twin)");
}

}  // namespace gpfd::env::twin
