#include "config_loading.hpp"

#include <filesystem>

#include "gpfd/builtin_configs.hpp"

namespace gpfd::app {

run::ExperimentConfig loadConfig(const std::string& config,
                                 const std::vector<std::string>& overrides,
                                 const std::string& fallback) {
  const std::string name = config.empty() ? fallback : config;
  if (config.empty() || !std::filesystem::exists(config)) {
    for (const auto& builtin : kBuiltinConfigs) {
      if (builtin.name == name) {
        return run::parseExperimentConfig(std::string(builtin.text), "configs/" + name + ".toml",
                                          overrides);
      }
    }
  }
  return run::loadExperimentConfig(config, overrides);
}

std::vector<std::string> builtinConfigNames() {
  std::vector<std::string> names;
  for (const auto& builtin : kBuiltinConfigs) names.emplace_back(builtin.name);
  return names;
}

}  // namespace gpfd::app
