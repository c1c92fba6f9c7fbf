// rl: stochastic policies linear in the features. Continuous actions: a Gaussian per action
// dimension; discrete actions: a softmax over the choices. Both give the gradient of the log
// likelihood of the action they sampled, for the likelihood-ratio gradient.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::rl {

struct PolicyOptions {
  // Gaussian policy. Actions are expressed in normalised units u in [-1, 1] per dimension,
  // mapped to the environment's box as centre + halfWidth * u (halfWidth = 1 for unbounded
  // dimensions), so that one set of Rprop step sizes suits every environment.
  // u ~ N(theta_i . phi, std^2); std in normalised units.
  double initialStd = 0.5;
  bool learnStd = false;  // When true, log std per dimension is a parameter (after the weights).
  double minStd = 0.01;
  double maxStd = 2.0;
};

// Parameters (one flat vector): the weights, row-major (outputs x featureDim), then, for a
// learned std, log std per action dimension. Outputs are the action dimensions (Gaussian) or
// the choices (softmax). Initial weights are 0.
class LinearPolicy {
 public:
  // Throws InputError for a discrete space with more than one action component.
  LinearPolicy(const env::ActionSpace& space, std::size_t featureDim, const PolicyOptions& options);

  bool continuous() const { return continuous_; }
  std::size_t outputs() const { return outputs_; }
  std::size_t featureDim() const { return featureDim_; }
  std::size_t actionComponents() const { return continuous_ ? outputs_ : 1; }
  Eigen::Index parameterCount() const { return params_.size(); }
  Eigen::VectorXd& parameters() { return params_; }
  const Eigen::VectorXd& parameters() const { return params_; }
  // Clamps a learned log std into [log minStd, log maxStd] (after an update).
  void clampParameters();

  // Samples an action for the features phi[0, featureDim()) into action[0, actionComponents())
  // (environment units) and adds d log pi(action | phi) / d params to grad[0, parameterCount()).
  // Returns false when the policy's outputs are not finite (the action is then unusable).
  bool sample(Rng& rng, const double* phi, double* action, double* grad);
  // The greedy action: the mean (Gaussian) or the most probable choice (softmax).
  bool greedy(const double* phi, double* action);

  // The pieces of sample() and greedy(), for learners that play many episodes side by side and
  // compute the outputs (theta_i . phi, summed over j in order from 0) themselves.
  // Gaussian: the standard deviation of output i (normalised units) and the action box mapping.
  double stdOf(std::size_t i) const;
  double centre(std::size_t i) const { return centre_[i]; }
  double halfWidth(std::size_t i) const { return halfWidth_[i]; }
  // Softmax: draws a choice from the logits z[0, outputs()) (overwritten), writes the likelihood
  // coefficients 1[k = choice] - p_k into coefficient[0, outputs()) and returns the choice.
  std::size_t drawChoice(double* z, Rng& rng, double* coefficient) const;

 private:
  bool computeOutputs(const double* phi);  // outputs_ values into out_; false if not finite.

  bool continuous_;
  std::size_t outputs_;
  std::size_t featureDim_;
  PolicyOptions options_;
  Eigen::VectorXd params_;
  std::vector<double> centre_, halfWidth_;  // Gaussian: action box mapping.
  std::vector<double> out_;                 // Means or logits (then probabilities).
  std::vector<double> coefficient_;         // Softmax likelihood coefficients.
};

}  // namespace gpfd::rl
