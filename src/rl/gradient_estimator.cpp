#include "gpfd/rl/gradient_estimator.hpp"

namespace gpfd::rl {

EpisodicGradientEstimator::EpisodicGradientEstimator(Eigen::Index parameterCount,
                                                     bool optimalBaseline)
    : optimalBaseline_(optimalBaseline),
      sumE_(Eigen::VectorXd::Zero(parameterCount)),
      sumER_(Eigen::VectorXd::Zero(parameterCount)),
      sumE2_(Eigen::VectorXd::Zero(parameterCount)),
      sumE2R_(Eigen::VectorXd::Zero(parameterCount)) {}

void EpisodicGradientEstimator::addEpisode(const Eigen::VectorXd& eligibility,
                                           double episodeReturn) {
  // With the optimal baseline the estimate is invariant to shifting every return by a constant;
  // shifting by the batch's first return makes it exactly 0 when all returns are equal (rounding
  // would otherwise leave ~1e-13 of random sign, on which Rprop still takes full steps).
  if (episodes_ == 0) offset_ = optimalBaseline_ ? episodeReturn : 0.0;
  ++episodes_;
  const double shifted = episodeReturn - offset_;
  sumE_ += eligibility;
  sumER_ += shifted * eligibility;
  sumE2_ += eligibility.cwiseAbs2();
  sumE2R_ += shifted * eligibility.cwiseAbs2();
}

void EpisodicGradientEstimator::baseline(Eigen::VectorXd& out) const {
  out.setZero(sumE_.size());
  if (!optimalBaseline_) return;
  for (Eigen::Index k = 0; k < out.size(); ++k) {
    if (sumE2_[k] > 0.0) out[k] = offset_ + sumE2R_[k] / sumE2_[k];
  }
}

void EpisodicGradientEstimator::gradient(Eigen::VectorXd& out) const {
  out.setZero(sumE_.size());
  if (episodes_ == 0) return;
  const double n = static_cast<double>(episodes_);
  for (Eigen::Index k = 0; k < out.size(); ++k) {
    double b = 0.0;
    if (optimalBaseline_ && sumE2_[k] > 0.0) b = sumE2R_[k] / sumE2_[k];
    out[k] = (sumER_[k] - b * sumE_[k]) / n;
  }
}

void EpisodicGradientEstimator::clear() {
  episodes_ = 0;
  offset_ = 0.0;
  sumE_.setZero();
  sumER_.setZero();
  sumE2_.setZero();
  sumE2R_.setZero();
}

}  // namespace gpfd::rl
