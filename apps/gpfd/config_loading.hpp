// Loading experiment configs for the commands: a TOML file, or the name of a shipped config.
#pragma once

#include <string>
#include <vector>

#include "gpfd/run/experiment_config.hpp"

namespace gpfd::app {

// `config` is a file path or a shipped config name (configs/NAME.toml, compiled in); empty means
// `fallback`. `overrides` are key=value assignments.
run::ExperimentConfig loadConfig(const std::string& config,
                                 const std::vector<std::string>& overrides,
                                 const std::string& fallback = "cartpole-quick");
// The names of the shipped configs.
std::vector<std::string> builtinConfigNames();

}  // namespace gpfd::app
