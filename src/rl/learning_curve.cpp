#include "gpfd/rl/learning_curve.hpp"

#include <algorithm>
#include <limits>

namespace gpfd::rl {

double LearningCurve::bestMeanReturn() const {
  double best = -std::numeric_limits<double>::infinity();
  for (const auto& p : points) best = std::max(best, p.meanReturn);
  return best;
}

double LearningCurve::finalMeanReturn() const {
  return points.empty() ? -std::numeric_limits<double>::infinity() : points.back().meanReturn;
}

}  // namespace gpfd::rl
