#include "trial_runner.hpp"

#include <fmt/format.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "gpfd/expr/wire.hpp"
#include "gpfd/fibers/scheduler.hpp"
#include "gpfd/run/run_grid.hpp"
#include "lockstep_group.hpp"

namespace gpfd::python {
namespace {

using Budget = run::LearningTask::Budget;

// (kind, genome wire record, with_original, fourier order): what a worker rebuilds the set from.
nb::tuple featuresToPython(const run::TrialFeatures& f) {
  const std::string blob = expr::wire::encodeGenome(f.genome);
  return nb::make_tuple(static_cast<int>(f.kind), nb::bytes(blob.data(), blob.size()),
                        f.withOriginal, f.fourierOrder);
}

run::TrialFeatures featuresFromPython(const nb::tuple& t, int variableCount) {
  run::TrialFeatures f;
  const int kind = nb::cast<int>(t[0]);
  if (kind < 0 || kind > static_cast<int>(run::TrialFeatures::kLastKind)) {
    throw std::invalid_argument(fmt::format("unknown kind of trial features {}", kind));
  }
  f.kind = static_cast<run::TrialFeatures::Kind>(kind);
  const auto genome = nb::cast<nb::bytes>(t[1]);
  f.genome =
      expr::wire::decodeGenome(std::string_view(genome.c_str(), genome.size()), variableCount);
  f.withOriginal = nb::cast<bool>(t[2]);
  f.fourierOrder = nb::cast<int>(t[3]);
  return f;
}

// A curve as plain Python values (floats are doubles: exact through pickle).
nb::tuple curveToPython(const rl::LearningCurve& c) {
  nb::list points;
  for (const auto& p : c.points) {
    points.append(nb::make_tuple(p.update, p.episodes, p.steps, p.meanReturn));
  }
  const auto& w = c.weights;
  return nb::make_tuple(points,
                        nb::make_tuple(w.rows, w.cols, nb::cast(w.values), nb::cast(w.shift),
                                       nb::cast(w.scale), w.bias),
                        c.episodes, c.steps, c.wallSeconds, c.diverged, c.divergedReason);
}

rl::LearningCurve curveFromPython(nb::handle value) {
  const auto t = nb::cast<nb::tuple>(value);
  rl::LearningCurve c;
  for (nb::handle point : nb::cast<nb::list>(t[0])) {
    const auto p = nb::cast<nb::tuple>(point);
    c.points.push_back({nb::cast<int>(p[0]), nb::cast<std::int64_t>(p[1]),
                        nb::cast<std::int64_t>(p[2]), nb::cast<double>(p[3])});
  }
  const auto w = nb::cast<nb::tuple>(t[1]);
  c.weights = {nb::cast<std::size_t>(w[0]),         nb::cast<std::size_t>(w[1]),
               nb::cast<std::vector<double>>(w[2]), nb::cast<std::vector<double>>(w[3]),
               nb::cast<std::vector<double>>(w[4]), nb::cast<bool>(w[5])};
  c.episodes = nb::cast<std::int64_t>(t[2]);
  c.steps = nb::cast<std::int64_t>(t[3]);
  c.wallSeconds = nb::cast<double>(t[4]);
  c.diverged = nb::cast<bool>(t[5]);
  c.divergedReason = nb::cast<std::string>(t[6]);
  return c;
}

class PythonTrialRunner final : public run::TrialRunner {
 public:
  explicit PythonTrialRunner(nb::object evaluator) : evaluator_(std::move(evaluator)) {}
  ~PythonTrialRunner() override {
    nb::gil_scoped_acquire gil;
    evaluator_.reset();
  }

  std::vector<std::vector<rl::LearningCurve>> run(
      const run::LearningTask& task, const run::TrialBatch& batch,
      const std::function<void(std::size_t)>& done) override {
    const std::size_t runs = batch.runs();
    std::vector<std::vector<rl::LearningCurve>> curves(batch.sets.size(),
                                                       std::vector<rl::LearningCurve>(runs));
    if (runs == 0) return curves;
    const std::string configText = run::formatExperimentConfig(task.config());
    nb::gil_scoped_acquire gil;
    const auto workers = nb::cast<std::size_t>(evaluator_.attr("workers"));
    // Runs played side by side in one call; on a vector form a fixed number (the trials of a
    // fitness evaluation), so that one seeded as a whole gives the same curves for any number of
    // workers (the evaluator groups the calls in lockstep groups).
    const std::size_t group =
        nb::cast<bool>(evaluator_.attr("lockstep"))
            ? static_cast<std::size_t>(std::max(1, task.config().trials))
            : run::runGroupSize(batch.sets.size(), runs, workers, task.config().trials);
    // Task j: runs [first, first + count) of set s, in this order.
    struct Slot {
      std::size_t set, first, count;
    };
    std::vector<Slot> slots;
    nb::list tasks;
    for (std::size_t s = 0; s < batch.sets.size(); ++s) {
      const nb::tuple features = featuresToPython(batch.sets[s]);
      for (std::size_t first = 0; first < runs; first += group) {
        const std::size_t count = std::min(group, runs - first);
        std::vector<std::uint64_t> seeds(batch.seeds[s].begin() + static_cast<long>(first),
                                         batch.seeds[s].begin() + static_cast<long>(first + count));
        tasks.append(nb::make_tuple(features, seeds));
        slots.push_back({s, first, count});
      }
    }
    const nb::object results =
        evaluator_.attr("run_trials")(configText, static_cast<int>(task.budget()), tasks);
    std::size_t j = 0;
    for (nb::handle result : results) {
      if (j == slots.size()) throw std::runtime_error("the trial runner returned too many tasks");
      const Slot& slot = slots[j++];
      const auto list = nb::cast<nb::list>(result);
      if (list.size() != slot.count) {
        throw std::runtime_error(fmt::format("the trial runner returned {} curves for {} runs",
                                             list.size(), slot.count));
      }
      for (std::size_t r = 0; r < slot.count; ++r) {
        curves[slot.set][slot.first + r] = curveFromPython(list[r]);
      }
      if (done) done(slot.count);
    }
    if (j != slots.size()) throw std::runtime_error("the trial runner returned too few tasks");
    return curves;
  }

 private:
  nb::object evaluator_;
};

std::shared_ptr<const run::LearningTask> taskOf(const std::string& configText, int budget) {
  if (budget < 0 || budget > static_cast<int>(Budget::Assessment)) {
    throw std::invalid_argument(fmt::format("unknown budget {}", budget));
  }
  return cachedTask(configText, static_cast<Budget>(budget));
}

std::vector<rl::LearningCurve> trainSet(const run::LearningTask& task,
                                        const run::TrialFeatures& set,
                                        const std::vector<std::uint64_t>& seeds) {
  const auto map = set.map(task);
  std::vector<Rng> rngs(seeds.begin(), seeds.end());
  return task.trainRuns(*map, rngs);
}

nb::list curvesToPython(const std::vector<rl::LearningCurve>& curves) {
  nb::list out;
  for (const auto& curve : curves) out.append(curveToPython(curve));
  return out;
}

// The learning runs of each (features, seeds), run k of a task seeded Rng(seeds[k]), played in one
// lockstep group (lockstep_group.hpp): the worker processes' task for validation, confirmation and
// assessment (a group of one where there is no vector form); their curves as plain values.
nb::list trainRunsGroup(const std::string& configText, int budget, const nb::list& tasks) {
  const auto owned = taskOf(configText, budget);  // Kept while in use: forgetCachedTasks may run.
  const run::LearningTask& task = *owned;
  std::vector<run::TrialFeatures> sets;
  std::vector<std::vector<std::uint64_t>> seeds;
  for (nb::handle t : tasks) {
    const auto pair = nb::cast<nb::tuple>(t);
    sets.push_back(
        featuresFromPython(nb::cast<nb::tuple>(pair[0]), static_cast<int>(task.stateDim())));
    seeds.push_back(nb::cast<std::vector<std::uint64_t>>(pair[1]));
  }
  std::vector<std::vector<rl::LearningCurve>> curves(sets.size());
  {
    nb::gil_scoped_release release;
    playInGroup(sets.size(), [&](std::size_t i) { curves[i] = trainSet(task, sets[i], seeds[i]); });
  }
  nb::list out;
  for (const auto& c : curves) out.append(curvesToPython(c));
  return out;
}

}  // namespace

std::shared_ptr<run::TrialRunner> pythonTrialRunner(nb::object evaluator) {
  return std::make_shared<PythonTrialRunner>(std::move(evaluator));
}

namespace {

// The tasks of cachedTask, by config text and budget, each with the count of the call that last
// used it; at most kCachedTasks (the least recently used dropped first).
constexpr std::size_t kCachedTasks = 16;
struct CachedTask {
  std::shared_ptr<const run::LearningTask> task;
  std::uint64_t lastUse = 0;
};
std::mutex cacheMutex;
std::map<std::pair<std::string, Budget>, CachedTask> cachedTasks;
std::uint64_t cacheUses = 0;

}  // namespace

std::shared_ptr<const run::LearningTask> cachedTask(const std::string& configText, Budget budget) {
  const std::pair key{configText, budget};
  {
    const std::lock_guard lock(cacheMutex);
    if (auto found = cachedTasks.find(key); found != cachedTasks.end()) {
      found->second.lastUse = ++cacheUses;
      return found->second.task;
    }
  }
  // Made without the lock: making it steps the environment (its sampled states), whose Python
  // may register a name, which forgets the cached tasks (forgetCachedTasks).
  auto task = std::make_shared<const run::LearningTask>(
      run::parseExperimentConfig(configText, "config"), budget);
  const std::lock_guard lock(cacheMutex);
  auto& entry = cachedTasks[key];
  if (!entry.task) entry.task = std::move(task);  // Else another thread's, made meanwhile.
  entry.lastUse = ++cacheUses;
  auto shared = entry.task;  // Copied before an eviction may drop `entry`.
  if (cachedTasks.size() > kCachedTasks) {
    cachedTasks.erase(std::ranges::min_element(cachedTasks, {},
                                               [](const auto& kv) { return kv.second.lastUse; }));
  }
  return shared;
}

void forgetCachedTasks() {
  const std::lock_guard lock(cacheMutex);
  cachedTasks.clear();  // A task in use lives on in its users' shared_ptr.
}

void bindTrialRunner(nb::module_& m) {
  m.def("on_thread_stack", &fibers::onThreadsOwnStack,
        "Whether the caller runs on its thread's own stack, not on a lockstep group's fiber: "
        "true for every call gpfd makes into Python (tests check it from an environment).");
  m.def("train_runs_group", &trainRunsGroup, nb::arg("config_text"), nb::arg("budget"),
        nb::arg("tasks"),
        "The learning runs of each (features, seeds), played in one lockstep group: the runs' "
        "episodes share one vector environment (the worker processes' task); their curves.");
}

}  // namespace gpfd::python
