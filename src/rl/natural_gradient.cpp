#include "gpfd/rl/natural_gradient.hpp"

#include <Eigen/Cholesky>
#include <cmath>

namespace gpfd::rl {

NaturalGradientStep::NaturalGradientStep(Eigen::Index parameterCount)
    : sumE_(Eigen::VectorXd::Zero(parameterCount)),
      sumER_(Eigen::VectorXd::Zero(parameterCount)),
      sumEE_(Eigen::MatrixXd::Zero(parameterCount, parameterCount)) {}

void NaturalGradientStep::addEpisode(const Eigen::VectorXd& eligibility, double episodeReturn,
                                     long steps) {
  if (episodes_ == 0) offset_ = episodeReturn;
  ++episodes_;
  steps_ += steps;
  const double shifted = episodeReturn - offset_;
  sumR_ += shifted;
  sumE_ += eligibility;
  sumER_ += shifted * eligibility;
  sumEE_.noalias() += eligibility * eligibility.transpose();
}

void NaturalGradientStep::step(double klPerStep, Eigen::VectorXd& out) const {
  out.setZero(sumE_.size());
  if (episodes_ < 2 || sumE_.size() == 0) return;
  const double n = static_cast<double>(episodes_);
  const Eigen::MatrixXd fisher = sumEE_ / n;
  const Eigen::VectorXd meanE = sumE_ / n;
  // The least-squares fit with a constant, in centred form: Cov(e) w = Cov(e, R). A ridge of a
  // millionth of the mean variance keeps it defined where parameters are redundant (a softmax's
  // choices, a constant feature) or outnumber the episodes.
  Eigen::MatrixXd covariance = fisher - meanE * meanE.transpose();
  const Eigen::VectorXd crossCovariance = sumER_ / n - meanE * (sumR_ / n);
  const double meanVariance = covariance.trace() / static_cast<double>(covariance.rows());
  if (!(meanVariance > 0.0)) {
    if (!std::isfinite(meanVariance)) out.setConstant(meanVariance);
    return;
  }
  covariance.diagonal().array() += 1e-6 * meanVariance;
  const Eigen::VectorXd w = covariance.ldlt().solve(crossCovariance);
  const double curvature = w.dot(fisher * w);
  if (!std::isfinite(curvature)) {
    out.setConstant(curvature);
    return;
  }
  if (!(curvature > 0.0)) return;
  const double meanSteps = static_cast<double>(steps_) / n;
  out = std::sqrt(2.0 * klPerStep * meanSteps / curvature) * w;
}

void NaturalGradientStep::clear() {
  episodes_ = 0;
  steps_ = 0;
  offset_ = 0.0;
  sumR_ = 0.0;
  sumE_.setZero();
  sumER_.setZero();
  sumEE_.setZero();
}

}  // namespace gpfd::rl
