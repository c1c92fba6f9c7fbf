// run: the independent learning runs of several feature maps (validation, re-measurement,
// assessment), trained on a pool of threads with a few runs of one map played together
// (LearningTask::trainRuns).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/run/learning_task.hpp"

namespace gpfd::run {

// How many runs of one map to train together when `sets` x `runs` runs are spread over
// `workers`: up to `trials` (a fitness evaluation's count), fewer where that would leave workers
// idle (at least two groups per worker where there are enough runs). Changes no curve.
std::size_t runGroupSize(std::size_t sets, std::size_t runs, std::size_t workers, int trials);

// curves[s][r]: run r of maps[s], drawing from Rng(seed(s, r)). Up to task.config().trials runs
// of one map are trained together (fewer where that would leave threads idle); the curves are
// the same bits whatever the grouping and the number of threads (0: all cores). done(n), when
// given, is called after each group of n finished runs (progress), from any thread.
std::vector<std::vector<rl::LearningCurve>> trainRunGrid(
    const LearningTask& task, const std::vector<const features::FeatureMap*>& maps,
    std::size_t runs, const std::function<std::uint64_t(std::size_t s, std::size_t r)>& seed,
    int threads, const std::function<void(std::size_t)>& done = {});

}  // namespace gpfd::run
