#include "gpfd/rl/learner.hpp"

namespace gpfd::rl {

std::vector<LearningCurve> Learner::trainRuns(const EnvironmentMaker& makeEnv,
                                              const features::FeatureMap& map, std::span<Rng> rngs,
                                              const RunPointCallback& onPoint) const {
  std::vector<LearningCurve> curves;
  curves.reserve(rngs.size());
  for (std::size_t k = 0; k < rngs.size(); ++k) {
    PointCallback point;
    if (onPoint) point = [&onPoint, k](const CurvePoint& p) { onPoint(k, p); };
    const auto env = makeEnv();
    curves.push_back(train(*env, map, rngs[k], point));
  }
  return curves;
}

}  // namespace gpfd::rl
