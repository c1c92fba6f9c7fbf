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

double trialFitness(const std::string& config, const std::vector<std::string>& overrides,
                    const FeatureSource& source, std::uint64_t seed) {
  const auto resolved = loadConfig(config, overrides);
  run::validate(resolved);
  const run::LearningTask task(resolved, run::LearningTask::Budget::Trial);
  const auto file = featuresFor(source, task);
  Rng rng(seed);
  try {
    return run::trialFitness(task, file.genome, rng);
  } catch (const std::invalid_argument& e) {  // Past the compiler's limits.
    throw InputError(e.what(), source.path.empty() ? source.name : source.path);
  }
}

}  // namespace gpfd::service
