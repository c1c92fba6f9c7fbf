#include "gpfd/service/configs.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "gpfd/builtin_configs.hpp"
#include "gpfd/io/suggest.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::service {
namespace {

// Whether `path` names something on disk; a path the system cannot even look up (a symlink loop,
// a name too long) is the user's mistake, named as such.
bool existsOnDisk(const std::string& path) {
  std::error_code ec;
  const bool exists = std::filesystem::exists(path, ec);
  if (ec) throw InputError("cannot read the config: " + ec.message(), path);
  return exists;
}

}  // namespace

run::ExperimentConfig loadConfig(const std::string& config,
                                 const std::vector<std::string>& overrides,
                                 const std::string& fallback) {
  const std::string name = config.empty() ? fallback : config;
  if (config.empty() || !existsOnDisk(config)) {
    for (const auto& builtin : kBuiltinConfigs) {
      if (builtin.name == name) {
        return run::parseExperimentConfig(std::string(builtin.text), "configs/" + name + ".toml",
                                          overrides);
      }
    }
    // A bare name (no directory, no .toml) was meant as a shipped config.
    if (name.find('/') == std::string::npos && !name.ends_with(".toml")) {
      const auto names = builtinConfigNames();
      const std::string suggestion = io::didYouMean(name, names);
      throw InputError(
          "neither a file nor a shipped config" +
              (suggestion.empty() ? fmt::format(" (shipped: {})", fmt::join(names, ", "))
                                  : suggestion),
          name);
    }
  }
  return run::loadExperimentConfig(config, overrides);
}

std::vector<std::string> builtinConfigNames() {
  std::vector<std::string> names;
  for (const auto& builtin : kBuiltinConfigs) names.emplace_back(builtin.name);
  return names;
}

}  // namespace gpfd::service
