// rl: the episodic natural actor-critic step (Peters & Schaal 2008, "Natural actor-critic",
// Neurocomputing 71(7-9), table 1, eNAC): the returns of a batch regressed on each episode's
// eligibility e = sum_t d log pi(a_t | s_t) / d theta and a constant,
//   R_i ~ e_i . w + J,
// give the natural gradient w (the vanilla gradient premultiplied by the inverse Fisher matrix);
// the step along it is sized so that the policy moves by a fixed KL divergence, as in a trust
// region (Schulman et al. 2015, "Trust region policy optimization", eq. 12 and appendix C):
//   theta += sqrt(2 kl T / (w' F w)) w,   F = < e e' >,
// with T the batch's mean episode length: F estimates the Fisher matrix of a whole episode, so kl
// is the mean divergence per step.
#pragma once

#include <Eigen/Core>

namespace gpfd::rl {

// Accumulates sums over a batch's episodes; no per-episode storage.
class NaturalGradientStep {
 public:
  explicit NaturalGradientStep(Eigen::Index parameterCount);

  void addEpisode(const Eigen::VectorXd& eligibility, double episodeReturn, long steps);
  long episodes() const { return episodes_; }
  // The step for the episodes added since the last clear(): 0 with fewer than two episodes, when
  // the returns do not vary with the eligibilities, or when w' F w is not positive. Non-finite
  // where the sums are.
  void step(double klPerStep, Eigen::VectorXd& out) const;
  void clear();

 private:
  long episodes_ = 0;
  long steps_ = 0;
  double offset_ = 0.0;  // Subtracted from every return (the first one): the fit's conditioning.
  double sumR_ = 0.0;
  Eigen::VectorXd sumE_, sumER_;
  Eigen::MatrixXd sumEE_;
};

}  // namespace gpfd::rl
