// rl: the episodic likelihood-ratio (REINFORCE) gradient estimate with the optimal
// per-parameter baseline of Peters & Schaal (2008, "Reinforcement learning of motor skills with
// policy gradients", Neural Networks 21(4), eq. 14-15):
//   g_k = < e_k (R - b_k) >,  b_k = < e_k^2 R > / < e_k^2 >,
// where e = sum_t d log pi(a_t | s_t) / d theta over an episode and R its (discounted) return.
#pragma once

#include <Eigen/Core>

namespace gpfd::rl {

// Accumulates sums over episodes; no per-episode storage.
class EpisodicGradientEstimator {
 public:
  EpisodicGradientEstimator(Eigen::Index parameterCount, bool optimalBaseline);

  void addEpisode(const Eigen::VectorXd& eligibility, double episodeReturn);
  long episodes() const { return episodes_; }
  // The estimate over the episodes added since the last clear(); 0 when there are none.
  void gradient(Eigen::VectorXd& out) const;
  // The baseline per parameter (0 without the optimal baseline or where < e_k^2 > = 0).
  void baseline(Eigen::VectorXd& out) const;
  void clear();

 private:
  bool optimalBaseline_;
  long episodes_ = 0;
  double offset_ = 0.0;  // Subtracted from every return (the first one, with the baseline).
  Eigen::VectorXd sumE_, sumER_, sumE2_, sumE2R_;
};

}  // namespace gpfd::rl
