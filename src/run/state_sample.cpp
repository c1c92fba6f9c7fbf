#include "gpfd/run/state_sample.hpp"

#include "gpfd/expr/eval.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/finite.hpp"

namespace gpfd::run {
std::vector<double> sampleVisitedStates(env::Environment& environment, std::size_t count,
                                        std::uint64_t seed, int maxEpisodeSteps) {
  Rng rng(seed);
  std::vector<double> states;
  std::vector<double> action(environment.actionSpace().components);
  const std::size_t budget = 100 * count;
  std::size_t taken = 0, steps = 0;
  const auto record = [&] {
    const auto state = environment.state();
    if (!allFinite(state)) return;
    states.insert(states.end(), state.begin(), state.end());
    ++taken;
  };
  while (taken < count && steps < budget) {
    environment.reset(rng);
    record();
    for (int t = 0; t < maxEpisodeSteps && taken < count && steps < budget; ++t, ++steps) {
      environment.sampleAction(rng, action);
      const auto result = environment.step(action);
      record();
      if (result.terminated || result.truncated) break;
    }
  }
  if (taken < count) {
    throw InputError("yields too few finite states to sample (" + std::to_string(taken) + " of " +
                         std::to_string(count) + ")",
                     "environment " + environment.name());
  }
  return states;
}

FeatureSample::FeatureSample(std::vector<double> states, std::size_t stateDim)
    : states_(std::move(states)), stateDim_(stateDim), rows_(states_.size() / stateDim) {}

std::vector<double> FeatureSample::column(const expr::Genome& genome, std::size_t k) const {
  std::vector<double> out(rows_);
  for (std::size_t r = 0; r < rows_; ++r) {
    out[r] = expr::evaluate(genome.feature(k), states_.data() + r * stateDim_);
  }
  return out;
}

std::vector<double> FeatureSample::variable(std::size_t i) const {
  std::vector<double> out(rows_);
  for (std::size_t r = 0; r < rows_; ++r) out[r] = states_[r * stateDim_ + i];
  return out;
}

}  // namespace gpfd::run
