// service: experiment configs as every front end reads them: a TOML file, or the name of a
// shipped config (configs/NAME.toml, compiled in), with key=value overrides.
#pragma once

#include <string>
#include <vector>

#include "gpfd/run/experiment_config.hpp"

namespace gpfd::service {

// The config of `gpfd evolve` and `gpfd.evolve` when none is given.
inline constexpr const char* kDefaultConfig = "cartpole-quick";

// `config` is a file path or a shipped config name; empty means `fallback`. `overrides` are
// key=value assignments (--set). InputError for a missing file, an unknown name (with a
// did-you-mean) or a bad key or value.
run::ExperimentConfig loadConfig(const std::string& config,
                                 const std::vector<std::string>& overrides,
                                 const std::string& fallback = kDefaultConfig);
// The names of the shipped configs.
std::vector<std::string> builtinConfigNames();

}  // namespace gpfd::service
