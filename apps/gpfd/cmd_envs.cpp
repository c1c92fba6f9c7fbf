// `gpfd envs`: lists every registered environment with its state variables, action space and
// parameters (defaults from a default-constructed instance).
#include <fmt/format.h>

#include <cstdio>

#include "command.hpp"
#include "gpfd/env/environment.hpp"

namespace gpfd::app {
namespace {

std::string describeActions(const env::ActionSpace& space) {
  if (space.continuous()) {
    std::vector<std::string> parts;
    for (std::size_t i = 0; i < space.components; ++i) {
      parts.push_back(
          fmt::format("{} in [{}, {}]", space.names.at(i), space.low[i], space.high[i]));
    }
    return "continuous: " + fmt::format("{}", fmt::join(parts, ", "));
  }
  if (space.components == 1) {
    return fmt::format("discrete: {} in 0..{}", space.names.at(0), space.choices - 1);
  }
  return fmt::format("discrete: ({}), legal values depend on the state",
                     fmt::join(space.names, ", "));
}

int runEnvs() {
  const auto& registry = env::Registry::global();
  std::string out;
  for (const auto& name : registry.names()) {
    const auto& info = registry.info(name);
    const auto instance = registry.make(name);
    fmt::format_to(std::back_inserter(out), "{}: {}\n", name, info.description);
    fmt::format_to(std::back_inserter(out), "  state ({}, with default parameters): {}\n",
                   instance->stateDim(), fmt::join(instance->stateNames(), ", "));
    fmt::format_to(std::back_inserter(out), "  actions: {}\n",
                   describeActions(instance->actionSpace()));
    out += "  parameters:\n";
    for (const auto& p : info.params) {
      fmt::format_to(std::back_inserter(out), "    {} = {}  ({})\n", p.name, p.defaultValue,
                     p.meaning);
    }
    out += "\n";
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return 0;
}

const CommandRegistration registration{
    "envs", [](CLI::App& app) {
      app.add_subcommand("envs",
                         "List the environments, their state variables, actions and parameters");
      return [] { return runEnvs(); };
    }};

}  // namespace
}  // namespace gpfd::app
