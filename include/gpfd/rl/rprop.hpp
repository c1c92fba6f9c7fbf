// rl: the Rprop update (iRprop-, Igel & Huesken 2000, "Improving the Rprop learning algorithm")
// used by the policy-gradient learner to climb the estimated gradient.
#pragma once

#include <Eigen/Core>

namespace gpfd::rl {

struct RpropConfig {
  double deltaMin = 0.01;
  double deltaInitial = 0.1;
  double deltaMax = 0.5;
  double increase = 1.2;  // eta+ (Riedmiller & Braun 1993).
  double decrease = 0.5;  // eta-.

  // The two settings of Girgin & Preux (section 4): (min, initial, max).
  static RpropConfig paperLarge() { return {0.01, 0.1, 0.5}; }
  static RpropConfig paperSmall() { return {0.002, 0.02, 0.1}; }
};

// Per-parameter step sizes and the previous gradient. Ascent: parameters move along the sign of
// the gradient (we maximise the return).
class Rprop {
 public:
  Rprop(const RpropConfig& config, Eigen::Index parameterCount);

  // iRprop-: where the gradient kept its sign, delta grows (capped at deltaMax); where it
  // flipped, delta shrinks (floored at deltaMin) and that parameter is not moved this time and
  // its stored gradient is set to 0. Then params += sign(gradient) * delta.
  void step(const Eigen::VectorXd& gradient, Eigen::VectorXd& params);

  const Eigen::VectorXd& deltas() const { return delta_; }

 private:
  RpropConfig config_;
  Eigen::VectorXd delta_;
  Eigen::VectorXd previous_;
};

}  // namespace gpfd::rl
