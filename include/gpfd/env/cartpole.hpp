// env: cart-pole balancing (Barto, Sutton & Anderson 1983; Gymnasium CartPole-v1), with the
// equations and constants of docs/benchmarks.md and the options of the Riedmiller group's CLSquare
// variant.
#pragma once

#include <array>

#include "gpfd/env/environment.hpp"
#include "gpfd/env/integrate.hpp"

namespace gpfd::env {

struct CartPoleConfig {
  double gravity = 9.8;                       // m/s^2 (CLSquare: 9.81).
  Integrator integrator = Integrator::Euler;  // Gymnasium: explicit Euler (CLSquare: rk4).
  double dt = 0.02;                           // Control interval in seconds.
  int substeps = 1;                           // Integration steps per interval (CLSquare: 10).
  double maxForce = 10.0;                     // Newtons: F in [-maxForce, maxForce].
  bool discrete = false;                      // Discrete: 0 -> -maxForce, 1 -> +maxForce.
  int maxSteps = 1000;                        // Truncation; 0 = no limit.

  // The parameters, declared once: names, defaults, ranges and meanings.
  static const ParamTable<CartPoleConfig>& table();
  static CartPoleConfig fromParams(const Params& params) { return table().read(params); }
};

// State (x, dx, th, dth) in m, m/s, rad, rad/s; th = 0 upright. Reward +1 per step, the failing
// step included; terminal when |x| > 2.4 or |th| > 12 degrees.
class CartPole final : public Environment {
 public:
  using State = std::array<double, 4>;

  explicit CartPole(CartPoleConfig config = {});
  static EnvInfo info();  // Name, description and factory, for the registry.

  std::string name() const override { return "cartpole"; }
  Params params() const override { return CartPoleConfig::table().write(config_); }
  const std::vector<std::string>& stateNames() const override;
  ActionSpace actionSpace() const override;
  void reset(Rng& rng) override;
  std::span<const double> state() const override { return state_; }
  void setState(std::span<const double> state) override;
  StepResult step(std::span<const double> action) override;
  std::vector<StateRange> typicalStateRanges() const override;
  // The state variables and the episode's step count.
  std::vector<std::uint64_t> snapshot() const override;
  void restore(std::span<const std::uint64_t> words) override;

  const CartPoleConfig& config() const { return config_; }
  // d/dt (x, dx, th, dth) at `s` under force `force` (docs/benchmarks.md).
  State derivative(const State& s, double force) const;
  bool terminal() const;
  double forceOf(std::span<const double> action) const;

 private:
  CartPoleConfig config_;
  State state_{};
  int steps_ = 0;
};

}  // namespace gpfd::env
