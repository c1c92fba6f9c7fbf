#include "gpfd/run/run_grid.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

namespace gpfd::run {

std::size_t runGroupSize(std::size_t sets, std::size_t runs, std::size_t workers, int trials) {
  return std::clamp<std::size_t>(sets * runs / (2 * std::max<std::size_t>(workers, 1)), 1,
                                 static_cast<std::size_t>(std::max(1, trials)));
}

std::vector<std::vector<rl::LearningCurve>> trainRunGrid(
    const LearningTask& task, const std::vector<const features::FeatureMap*>& maps,
    std::size_t runs, const std::function<std::uint64_t(std::size_t s, std::size_t r)>& seed,
    int threads, const std::function<void(std::size_t)>& done) {
  std::vector<std::vector<rl::LearningCurve>> curves(maps.size(),
                                                     std::vector<rl::LearningCurve>(runs));
  if (runs == 0 || maps.empty()) return curves;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  const std::size_t group = runGroupSize(
      maps.size(), runs, static_cast<std::size_t>(arena.max_concurrency()), task.config().trials);
  const std::size_t groupsPerMap = (runs + group - 1) / group;
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, maps.size() * groupsPerMap, [&](std::size_t job) {
      const std::size_t s = job / groupsPerMap, first = job % groupsPerMap * group;
      const std::size_t count = std::min(group, runs - first);
      std::vector<Rng> rngs;
      for (std::size_t r = first; r < first + count; ++r) rngs.emplace_back(seed(s, r));
      auto trained = task.trainRuns(*maps[s], rngs);
      std::move(trained.begin(), trained.end(), curves[s].begin() + static_cast<long>(first));
      if (done) done(count);
    });
  });
  return curves;
}

}  // namespace gpfd::run
