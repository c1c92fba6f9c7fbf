// service: a feature set named in a request: a features file to read, or one already read (the
// Python package's FeatureSet), checked against the task it is used for.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gpfd/expr/features_file.hpp"
#include "gpfd/run/learning_task.hpp"

namespace gpfd::service {

struct FeatureSource {
  std::string name;  // Empty: the file's stem.
  std::string path;  // Read when `file` is empty.
  std::optional<expr::FeaturesFile> file;
};

// The source's features file, read, or checked: it must be for the task's environment (when it
// names one) and read the task's state variables. InputError naming the source otherwise.
expr::FeaturesFile featuresFor(const FeatureSource& source, const run::LearningTask& task);

// How evaluations run: play(n, job) calls job(i) once for each i < n, in any order or at once.
using PlayJobs = std::function<void(std::size_t n, const std::function<void(std::size_t)>& job)>;
// GP's fitness of each source with the same seed: the mean score of the config's short learning
// trials, as one evaluation of `gpfd evolve` computes it (run::trialFitness with Rng(seed)); the
// evaluations run by `play` (empty: one after another; Python plays them in one lockstep group).
std::vector<double> trialFitnesses(const std::string& config,
                                   const std::vector<std::string>& overrides,
                                   const std::vector<FeatureSource>& sources, std::uint64_t seed,
                                   const PlayJobs& play = {});

}  // namespace gpfd::service
