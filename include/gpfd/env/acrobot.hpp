// env: Acrobot, the two-link underactuated pendulum (Sutton & Barto 1998, section 11.3; Spong
// 1995; Gymnasium Acrobot-v1), with the equations and constants of docs/benchmarks.md.
#pragma once

#include <array>

#include "gpfd/env/environment.hpp"
#include "gpfd/env/integrate.hpp"

namespace gpfd::env {

struct AcrobotConfig {
  enum class Dynamics { Book, Nips };
  Dynamics dynamics = Dynamics::Book;  // "nips" drops the -m2 l1 lc2 dth1^2 sin th2 term.
  Integrator integrator = Integrator::Rk4;
  double dt = 0.2;         // Control interval in seconds (torque held).
  int substeps = 1;        // Integration steps per control interval; wrap and clip after each.
  double maxTorque = 1.0;  // Continuous: tau in [-maxTorque, maxTorque]; discrete: {-1,0,1} x it.
  bool discrete = false;   // Actions: continuous torque (default) or 3 discrete choices.
  int maxSteps = 500;      // Truncation after this many steps; 0 = no limit.

  // The parameters, declared once: names, defaults, ranges and meanings.
  static const ParamTable<AcrobotConfig>& table();
  static AcrobotConfig fromParams(const Params& params) { return table().read(params); }
};

// State (th1, th2, dth1, dth2) in rad and rad/s; th1 = 0 hangs down, th2 relative to link 1.
// Reward -1 per step, 0 on the terminal step (tip above the bar: -cos th1 - cos(th1+th2) > 1).
class Acrobot final : public Environment {
 public:
  using State = std::array<double, 4>;

  explicit Acrobot(AcrobotConfig config = {});
  static EnvInfo info();  // Name, description and factory, for the registry.

  std::string name() const override { return "acrobot"; }
  Params params() const override { return AcrobotConfig::table().write(config_); }
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

  const AcrobotConfig& config() const { return config_; }
  // d/dt (th1, th2, dth1, dth2) at `s` under torque `tau` (docs/benchmarks.md).
  State derivative(const State& s, double tau) const;
  bool terminal() const;
  // The torque an action stands for (clipped; NaN -> 0; discrete index -> torque).
  double torqueOf(std::span<const double> action) const;

 private:
  AcrobotConfig config_;
  State state_{};
  int steps_ = 0;
};

}  // namespace gpfd::env
