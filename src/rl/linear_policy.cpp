#include "gpfd/rl/linear_policy.hpp"

#include <algorithm>
#include <cmath>

#include "gpfd/util/error.hpp"
#include "gpfd/util/ziggurat.hpp"

namespace gpfd::rl {

LinearPolicy::LinearPolicy(const env::ActionSpace& space, std::size_t featureDim,
                           const PolicyOptions& options)
    : continuous_(space.continuous()), featureDim_(featureDim), options_(options) {
  if (continuous_) {
    outputs_ = space.low.size();
    if (outputs_ == 0 || space.high.size() != outputs_) {
      throw InputError("continuous action space without bounds per dimension", "policy");
    }
    for (std::size_t i = 0; i < outputs_; ++i) {
      const double lo = space.low[i], hi = space.high[i];
      const bool bounded = std::isfinite(lo) && std::isfinite(hi) && hi > lo;
      centre_.push_back(bounded ? 0.5 * (lo + hi) : 0.0);
      halfWidth_.push_back(bounded ? 0.5 * (hi - lo) : 1.0);
    }
    if (!(options.initialStd > 0.0) || !(options.minStd > 0.0) ||
        !(options.maxStd >= options.minStd)) {
      throw InputError("the policy's standard deviations must be positive, min <= max", "policy");
    }
  } else {
    if (space.components != 1 || space.choices.front() < 2) {
      throw InputError("a softmax policy needs a one-component discrete action with >= 2 choices",
                       "policy");
    }
    outputs_ = static_cast<std::size_t>(space.choices.front());
  }
  const std::size_t extra = (continuous_ && options.learnStd) ? outputs_ : 0;
  params_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(outputs_ * featureDim_ + extra));
  for (std::size_t i = 0; i < extra; ++i) {
    params_[static_cast<Eigen::Index>(outputs_ * featureDim_ + i)] = std::log(options.initialStd);
  }
  out_.assign(outputs_, 0.0);
  coefficient_.assign(outputs_, 0.0);
}

void LinearPolicy::clampParameters() {
  if (!(continuous_ && options_.learnStd)) return;
  const double lo = std::log(options_.minStd), hi = std::log(options_.maxStd);
  for (std::size_t i = 0; i < outputs_; ++i) {
    double& v = params_[static_cast<Eigen::Index>(outputs_ * featureDim_ + i)];
    v = std::clamp(v, lo, hi);
  }
}

bool LinearPolicy::computeOutputs(const double* phi) {
  const double* w = params_.data();
  bool finite = true;
  for (std::size_t i = 0; i < outputs_; ++i) {
    double s = 0.0;
    const double* row = w + i * featureDim_;
    for (std::size_t j = 0; j < featureDim_; ++j) s += row[j] * phi[j];
    out_[i] = s;
    finite = finite && std::isfinite(s);
  }
  return finite;
}

double LinearPolicy::stdOf(std::size_t i) const {
  return options_.learnStd
             ? std::exp(params_[static_cast<Eigen::Index>(outputs_ * featureDim_ + i)])
             : options_.initialStd;
}

std::size_t LinearPolicy::drawChoice(double* z, Rng& rng, double* coefficient) const {
  // Softmax, shifted by the largest logit: p_k = exp(z_k - max) / sum.
  const double top = *std::max_element(z, z + outputs_);
  double total = 0.0;
  const bool finiteTop = std::isfinite(top);
  for (std::size_t k = 0; k < outputs_; ++k) {
    // exp(+0) is exactly 1 (C's Annex F): where z_k = top (finite), z_k - top is +0, and the
    // largest logits skip libm's call.
    z[k] = finiteTop && z[k] == top ? 1.0 : std::exp(z[k] - top);
    total += z[k];
  }
  const double draw = rng.uniform() * total;
  std::size_t chosen = outputs_ - 1;
  double cumulative = 0.0;
  for (std::size_t k = 0; k < outputs_; ++k) {
    cumulative += z[k];
    if (draw < cumulative) {
      chosen = k;
      break;
    }
  }
  // d log p_a / d theta_kj = (1[k = a] - p_k) phi_j.
  for (std::size_t k = 0; k < outputs_; ++k) {
    coefficient[k] = (k == chosen ? 1.0 : 0.0) - z[k] / total;
  }
  return chosen;
}

bool LinearPolicy::sample(Rng& rng, const double* phi, double* action, double* grad) {
  if (!computeOutputs(phi)) return false;
  if (continuous_) {
    const std::size_t weightCount = outputs_ * featureDim_;
    for (std::size_t i = 0; i < outputs_; ++i) {
      const double sd = stdOf(i);
      const double eps = standardNormal(rng);
      const double u = out_[i] + sd * eps;
      action[i] = centre_[i] + halfWidth_[i] * u;
      // Gaussian log likelihood: d/d theta_ij = (u - mu_i) / sd^2 * phi_j,
      // d/d log sd_i = (u - mu_i)^2 / sd^2 - 1.
      const double coefficient = eps / sd;
      double* g = grad + i * featureDim_;
      for (std::size_t j = 0; j < featureDim_; ++j) g[j] += coefficient * phi[j];
      if (options_.learnStd) grad[weightCount + i] += eps * eps - 1.0;
    }
    return true;
  }
  action[0] = static_cast<double>(drawChoice(out_.data(), rng, coefficient_.data()));
  for (std::size_t k = 0; k < outputs_; ++k) {
    double* g = grad + k * featureDim_;
    for (std::size_t j = 0; j < featureDim_; ++j) g[j] += coefficient_[k] * phi[j];
  }
  return true;
}

bool LinearPolicy::greedy(const double* phi, double* action) {
  if (!computeOutputs(phi)) return false;
  if (continuous_) {
    for (std::size_t i = 0; i < outputs_; ++i) action[i] = centre_[i] + halfWidth_[i] * out_[i];
  } else {
    action[0] = static_cast<double>(std::max_element(out_.begin(), out_.end()) - out_.begin());
  }
  return true;
}

}  // namespace gpfd::rl
