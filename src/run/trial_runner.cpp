#include "gpfd/run/trial_runner.hpp"

#include <stdexcept>

#include "gpfd/run/assessment.hpp"
#include "gpfd/run/run_grid.hpp"

namespace gpfd::run {

TrialFeatures TrialFeatures::ofGenome(expr::Genome genome, bool withOriginal) {
  TrialFeatures features;
  features.kind = Kind::Genome;
  features.genome = std::move(genome);
  features.withOriginal = withOriginal;
  return features;
}

TrialFeatures TrialFeatures::fourier(int order) {
  TrialFeatures features;
  features.kind = Kind::Fourier;
  features.fourierOrder = order;
  return features;
}

TrialFeatures TrialFeatures::noLearning() {
  TrialFeatures features;
  features.kind = Kind::NoLearning;
  return features;
}

std::shared_ptr<const features::FeatureMap> TrialFeatures::map(const LearningTask& task) const {
  switch (kind) {
    case Kind::Original:
      return std::make_shared<const features::RawFeatureMap>(task.stateDim());
    case Kind::Genome:
      return genomeFeatureMap(genome, task.stateDim(), withOriginal);
    case Kind::Fourier:
      return fourierBasis(task, fourierOrder);
    case Kind::NoLearning:
      return std::make_shared<const features::ZeroFeatureMap>(task.stateDim());
  }
  throw std::logic_error("unknown kind of trial features");
}

std::vector<std::vector<rl::LearningCurve>> ThreadTrialRunner::run(
    const LearningTask& task, const TrialBatch& batch,
    const std::function<void(std::size_t)>& done) {
  std::vector<std::shared_ptr<const features::FeatureMap>> maps;
  std::vector<const features::FeatureMap*> pointers;
  for (const auto& set : batch.sets) {
    maps.push_back(set.map(task));
    pointers.push_back(maps.back().get());
  }
  return trainRunGrid(
      task, pointers, batch.runs(), [&](std::size_t s, std::size_t r) { return batch.seeds[s][r]; },
      threads_, done);
}

}  // namespace gpfd::run
