// run: configs read back from a results directory (a resume's config.toml, a checkpoint's
// config). Such a directory is data, not code, wherever it came from: reading its config loads
// none of the plug-ins it names (`plugins`); each must be loaded already (`gpfd --plugin FILE`),
// else InputError naming it. Otherwise as parseExperimentConfig and loadExperimentConfig.
#pragma once

#include <string>

#include "gpfd/run/experiment_config.hpp"

namespace gpfd::run {

ExperimentConfig parseStoredExperimentConfig(const std::string& text, const std::string& source);
ExperimentConfig loadStoredExperimentConfig(const std::string& path);

}  // namespace gpfd::run
