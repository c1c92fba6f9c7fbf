#include "gpfd/rl/learning_curve.hpp"

#include <limits>

namespace gpfd::rl {

double LearningCurve::finalMeanReturn() const {
  return points.empty() ? -std::numeric_limits<double>::infinity() : points.back().meanReturn;
}

}  // namespace gpfd::rl
