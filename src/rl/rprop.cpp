#include "gpfd/rl/rprop.hpp"

#include <algorithm>

namespace gpfd::rl {

Rprop::Rprop(const RpropConfig& config, Eigen::Index parameterCount)
    : config_(config),
      delta_(Eigen::VectorXd::Constant(parameterCount, config.deltaInitial)),
      previous_(Eigen::VectorXd::Zero(parameterCount)) {}

void Rprop::step(const Eigen::VectorXd& gradient, Eigen::VectorXd& params) {
  for (Eigen::Index k = 0; k < params.size(); ++k) {
    double g = gradient[k];
    const double product = g * previous_[k];
    if (product > 0.0) {
      delta_[k] = std::min(delta_[k] * config_.increase, config_.deltaMax);
    } else if (product < 0.0) {
      delta_[k] = std::max(delta_[k] * config_.decrease, config_.deltaMin);
      g = 0.0;
    }
    if (g > 0.0) {
      params[k] += delta_[k];
    } else if (g < 0.0) {
      params[k] -= delta_[k];
    }
    previous_[k] = g;
  }
}

}  // namespace gpfd::rl
