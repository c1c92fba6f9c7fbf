// env: the n-segment swimmer in a viscous fluid (R. Coulom, PhD thesis 2002, appendix B), with the
// equations of docs/benchmarks.md.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/env/integrate.hpp"
#include "gpfd/env/swimmer_fixed_size.hpp"

namespace gpfd::env {

// Defaults marked (ours) are choices the sources leave open; docs/environments.md explains them.
struct SwimmerConfig {
  int segments = 3;                           // n >= 2 (the paper: 3 and 5).
  Integrator integrator = Integrator::Euler;  // Coulom integrates with explicit Euler.
  double dt = 0.1;                            // Control interval in seconds (ours).
  int substeps = 10;                          // Integration steps per interval: h = 0.01 s (ours).
  double maxTorque = 5.0;                     // u_j in [-maxTorque, maxTorque].
  int horizon = 100;                          // Truncation after this many steps (ours); 0 = none.
  double viscosity = 10.0;                    // Fluid viscosity k (0 = no drag, for tests).
  double startAngleNoise = 0.1;               // Reset: th_i ~ U(-a, a) around 0, at rest (ours).

  // The parameters, declared once: names, defaults, ranges and meanings.
  static const ParamTable<SwimmerConfig>& table();
  static SwimmerConfig fromParams(const Params& params) { return table().read(params); }
};

// State (dGx, dGy, th1, dth1, ..., thn, dthn): 2n + 2 values; velocity of the centre of mass in
// m/s, segment angles in rad (wrapped into [-pi, pi]) and their rates in rad/s. Action: n - 1
// joint torques. Reward per step: dGx * dt after the step (the distance swum along x).
// Every segment has mass 1, length 1 and moment of inertia 1/12.
class Swimmer final : public Environment {
 public:
  explicit Swimmer(SwimmerConfig config = {});
  static EnvInfo info();  // Name, description and factory, for the registry.

  std::string name() const override { return "swimmer"; }
  Params params() const override { return SwimmerConfig::table().write(config_); }
  const std::vector<std::string>& stateNames() const override { return names_; }
  ActionSpace actionSpace() const override;
  void reset(Rng& rng) override;
  std::span<const double> state() const override { return state_; }
  void setState(std::span<const double> state) override;
  StepResult step(std::span<const double> action) override;
  std::vector<StateRange> typicalStateRanges() const override;
  // The state variables and the episode's step count.
  std::vector<std::uint64_t> snapshot() const override;
  void restore(std::span<const std::uint64_t> words) override;
  // Its config and the reference solver switch (not a parameter).
  std::unique_ptr<Environment> freshCopy() const override;

  const SwimmerConfig& config() const { return config_; }
  int segments() const { return n_; }
  // d/dt state at `state` (2n + 2 values) under joint torques `torque` (n - 1 values, used as
  // given), written to `out` (2n + 2 values). Solves the linear system of docs/benchmarks.md: with
  // the fixed-size kernel (swimmer_fixed_size.hpp) for n <= kSwimmerFixedMaxSegments, otherwise
  // with derivativeReference.
  void derivative(std::span<const double> state, std::span<const double> torque,
                  std::span<double> out);
  // The same with run-time sized Eigen matrices and Eigen's PartialPivLU: the original
  // implementation, kept as the reference for tests and benchmarks.
  void derivativeReference(std::span<const double> state, std::span<const double> torque,
                           std::span<double> out);
  // When on, step() and derivative() use derivativeReference (for tests and benchmarks; default
  // off).
  void setReferenceSolver(bool on) { referenceSolver_ = on; }
  // The body constants of the fixed-size kernel when step() uses it, else nullptr (the batched
  // swimmer, env/batch.hpp, runs the same kernel).
  const SwimmerBody* fixedSizeBody() const { return fixedSize() ? &body_ : nullptr; }

 private:
  void integrateReference(double h);

  bool fixedSize() const { return !referenceSolver_ && fixedSizeKernel_; }

  SwimmerConfig config_;
  int n_;
  std::vector<std::string> names_;
  std::vector<double> state_;
  std::vector<double> torque_;
  int steps_ = 0;

  // Constants of the body: mass, length and inertia per segment, and the coupling matrix
  // couple_(i, j) = sum_k w_ik m_k (w_kj - wbar_j) with w_ij = 1 (j < i), 1/2 (j = i), 0 (j > i),
  // wbar_j = sum_k m_k w_kj / M (from eliminating A''_0 and the internal forces).
  std::vector<double> mass_, length_, inertia_, massWeight_;
  double totalMass_ = 0.0;
  Eigen::MatrixXd couple_;
  // The same constants for the fixed-size kernel, used when n <= kSwimmerFixedMaxSegments and C
  // is symmetric (always, for a body of equal segments).
  SwimmerBody body_;
  bool fixedSizeKernel_ = false;
  bool referenceSolver_ = false;

  // Scratch, sized once.
  Eigen::MatrixXd system_;
  Eigen::VectorXd rhs_, solution_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  std::vector<double> cos_, sin_, force_x_, force_y_, k1_, k2_, k3_, k4_, tmp_;
};

}  // namespace gpfd::env
