#include "gpfd/service/feature_source.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "gpfd/service/configs.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::service {

expr::FeaturesFile featuresFor(const FeatureSource& source, const run::LearningTask& task) {
  const auto& env = task.config().env;
  if (!source.file) return expr::readFeaturesFile(source.path, task.stateNames(), env);
  const auto& file = *source.file;
  if (!file.env.empty() && file.env != env) {
    throw InputError("the features are for " + file.env + ", not " + env, source.name);
  }
  if (file.variables != task.stateNames()) {
    throw InputError(
        fmt::format("the features read {} but {} has {}", fmt::join(file.variables, ", "), env,
                    fmt::join(task.stateNames(), ", ")),
        source.name);
  }
  return file;
}

std::vector<double> trialFitnesses(const std::string& config,
                                   const std::vector<std::string>& overrides,
                                   const std::vector<FeatureSource>& sources, std::uint64_t seed,
                                   const PlayJobs& play) {
  const auto resolved = loadConfig(config, overrides);
  run::validate(resolved);
  const run::LearningTask task(resolved, run::LearningTask::Budget::Trial);
  std::vector<expr::FeaturesFile> files;
  for (const FeatureSource& source : sources) files.push_back(featuresFor(source, task));
  std::vector<double> fitness(sources.size(), 0.0);
  const auto evaluate = [&](std::size_t i) {
    Rng rng(seed);
    try {
      fitness[i] = run::trialFitness(task, files[i].genome, rng);
    } catch (const std::invalid_argument& e) {  // Past the compiler's limits.
      const FeatureSource& source = sources[i];
      throw InputError(e.what(), source.path.empty() ? source.name : source.path);
    }
  };
  if (play) {
    play(sources.size(), evaluate);
  } else {
    for (std::size_t i = 0; i < sources.size(); ++i) evaluate(i);
  }
  return fitness;
}

}  // namespace gpfd::service
