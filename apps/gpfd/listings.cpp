#include "listings.hpp"

#include <fmt/format.h>

#include <iterator>

#include "gpfd/env/environment.hpp"
#include "gpfd/rl/learner.hpp"

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
    return fmt::format("discrete: {} in 0..{}", space.names.at(0), space.choices.front() - 1);
  }
  return fmt::format("discrete: ({}), legal values depend on the state",
                     fmt::join(space.names, ", "));
}

void describeParams(std::string& out, const std::vector<ParamSpec>& params) {
  out += "  parameters:\n";
  for (const auto& p : params) {
    fmt::format_to(std::back_inserter(out), "    {} = {}  in {}: {}\n", p.name,
                   p.defaultValue.empty() ? "\"\"" : p.defaultValue, p.range, p.meaning);
  }
}

// Every entry of `registry`: "name: description", the lines `details(out, info)` adds, and its
// parameters.
template <typename Registry, typename Details>
std::string describe(const Registry& registry, const Details& details) {
  std::string out;
  for (const auto& name : registry.names()) {
    const auto& info = registry.info(name);
    fmt::format_to(std::back_inserter(out), "{}: {}\n", name, info.description);
    details(out, info);
    describeParams(out, info.params);
    out += "\n";
  }
  return out;
}

}  // namespace

std::string describeEnvironments() {
  const auto& registry = env::Registry::global();
  return describe(registry, [&](std::string& out, const env::EnvInfo& info) {
    const auto instance = registry.make(info.name);
    fmt::format_to(std::back_inserter(out), "  state ({}, with default parameters): {}\n",
                   instance->stateDim(), fmt::join(instance->stateNames(), ", "));
    fmt::format_to(std::back_inserter(out), "  actions: {}\n",
                   describeActions(instance->actionSpace()));
    fmt::format_to(std::back_inserter(out), "  default learner: {}; typical state ranges: {}\n",
                   info.defaultLearner,
                   instance->typicalStateRanges().empty() ? "unknown (no Fourier basis)"
                                                          : "known (Fourier basis available)");
  });
}

std::string describeLearners() {
  return describe(rl::LearnerRegistry::global(), [](std::string& out, const rl::LearnerInfo& info) {
    fmt::format_to(std::back_inserter(out), "  needs: {}\n", info.needs);
    fmt::format_to(std::back_inserter(out), "  budget: {} (one curve row per {})\n",
                   info.budgetParam, info.rowName);
  });
}

std::string learnerParamSummary() {
  const auto& registry = rl::LearnerRegistry::global();
  std::string out;
  for (const auto& name : registry.names()) {
    fmt::format_to(std::back_inserter(out), "  {}: {}\n", name,
                   fmt::join(paramNames(registry.info(name).params), ", "));
  }
  return out;
}

}  // namespace gpfd::app
