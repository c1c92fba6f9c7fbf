// run: a sample of the states an environment visits, on which feature sets are compared without
// training (redundancy, normalisation). States come from episodes played with uniformly random
// legal actions from the environment's start distribution: roughly what a learner sees at first.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/expr/genome.hpp"

namespace gpfd::run {

// `count` visited states, row after row (count x env.stateDim() values), from episodes of at most
// `maxEpisodeSteps` steps seeded from `seed`. Non-finite states are skipped; InputError when the
// environment yields none in 100 * count steps.
std::vector<double> sampleVisitedStates(env::Environment& environment, std::size_t count,
                                        std::uint64_t seed, int maxEpisodeSteps = 200);

// A genome's features on sampled states: one column of `rows` values per feature, computed by the
// reference interpreter.
class FeatureSample {
 public:
  FeatureSample(std::vector<double> states, std::size_t stateDim);
  std::size_t rows() const { return rows_; }
  std::size_t stateDim() const { return stateDim_; }
  // Values of feature `k` of `genome` on every sampled state.
  std::vector<double> column(const expr::Genome& genome, std::size_t k) const;
  // Values of state variable `i` on every sampled state.
  std::vector<double> variable(std::size_t i) const;

 private:
  std::vector<double> states_;
  std::size_t stateDim_;
  std::size_t rows_;
};

}  // namespace gpfd::run
