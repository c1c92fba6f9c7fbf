// run: where batches of learning trials run (validation, confirmation, re-measurement,
// assessment). A trial's curve is a pure function of its features, its budget and its seed, so
// every runner gives the same curves: the default trains them on threads of this process; the
// Python package hands them to its worker processes (an environment stepped in Python; on a
// vector form seeded as a whole, also of the fixed lockstep group it plays in,
// python/src/lockstep_group.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "gpfd/expr/genome.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/run/learning_task.hpp"

namespace gpfd::run {

// A feature set as any process that holds the task's config can rebuild it.
struct TrialFeatures {
  // NoLearning: one feature that is always 0 (features::ZeroFeatureMap), the reference of a
  // policy that cannot depend on the state (docs/discovery.md, "The no-learning reference").
  enum class Kind { Original, Genome, Fourier, NoLearning };
  static constexpr Kind kLastKind = Kind::NoLearning;
  Kind kind = Kind::Original;
  expr::Genome genome;        // Kind::Genome: as the learner sees it (LearningTask::prepared).
  bool withOriginal = false;  // Kind::Genome: the original variables appended.
  int fourierOrder = 0;       // Kind::Fourier: the order of the basis (fourierFeatureSet).

  static TrialFeatures original() { return {}; }
  static TrialFeatures ofGenome(expr::Genome genome, bool withOriginal);
  static TrialFeatures fourier(int order);
  static TrialFeatures noLearning();

  // The feature map: the raw state, genomeFeatureMap(genome, dim, withOriginal), the task's
  // Fourier basis, or a ZeroFeatureMap. std::invalid_argument for a genome past the compiler's
  // limits; InputError for a Fourier basis of an environment without typical state ranges.
  std::shared_ptr<const features::FeatureMap> map(const LearningTask& task) const;
};

// The trials of one batch: run r of set s trains sets[s] drawing from Rng(seeds[s][r]).
struct TrialBatch {
  std::vector<TrialFeatures> sets;
  std::vector<std::vector<std::uint64_t>> seeds;  // One row per set, all of one length.

  std::size_t runs() const { return seeds.empty() ? 0 : seeds.front().size(); }
};

class TrialRunner {
 public:
  virtual ~TrialRunner() = default;
  // curves[s][r] of the batch, trained as `task` (its config and budget) trains. done(n), when
  // given, is called after each n finished runs (progress), from any thread.
  virtual std::vector<std::vector<rl::LearningCurve>> run(
      const LearningTask& task, const TrialBatch& batch,
      const std::function<void(std::size_t)>& done) = 0;
};

// Trains the batch on `threads` threads of this process (0: all cores), a few runs of a set
// played together (trainRunGrid).
class ThreadTrialRunner final : public TrialRunner {
 public:
  explicit ThreadTrialRunner(int threads) : threads_(threads) {}
  std::vector<std::vector<rl::LearningCurve>> run(
      const LearningTask& task, const TrialBatch& batch,
      const std::function<void(std::size_t)>& done) override;

 private:
  int threads_;
};

}  // namespace gpfd::run
