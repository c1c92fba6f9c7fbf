#include <fmt/format.h>

#include "gpfd/env/acrobot.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/env/swimmer.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

void addBuiltIns(Registry& registry) {
  registry.add({"acrobot",
                "two-link underactuated pendulum; swing the tip above the bar (Sutton & Barto; "
                "Gymnasium Acrobot-v1)",
                AcrobotConfig::paramSpecs(), [](const Params& p) {
                  return std::make_unique<Acrobot>(AcrobotConfig::fromParams(p));
                }});
  registry.add({"cartpole", "pole balancing on a cart (Barto et al. 1983; Gymnasium CartPole-v1)",
                CartPoleConfig::paramSpecs(), [](const Params& p) {
                  return std::make_unique<CartPole>(CartPoleConfig::fromParams(p));
                }});
  registry.add(
      {"swimmer", "n-segment swimmer in a viscous fluid; swim along x (Coulom 2002, appendix B)",
       SwimmerConfig::paramSpecs(),
       [](const Params& p) { return std::make_unique<Swimmer>(SwimmerConfig::fromParams(p)); }});
  registry.add(
      {"tetris", "Tetris with the 7 tetrominoes; reward = rows removed (the paper: 12 x 8)",
       TetrisConfig::paramSpecs(),
       [](const Params& p) { return std::make_unique<Tetris>(TetrisConfig::fromParams(p)); }});
}

}  // namespace

Registry& Registry::global() {
  static Registry registry = [] {
    Registry r;
    addBuiltIns(r);
    return r;
  }();
  return registry;
}

void Registry::add(EnvInfo info) {
  if (info.name.empty() || !info.make) {
    throw InputError("an environment needs a name and a factory", "environment registry");
  }
  if (entries_.count(info.name)) {
    throw InputError(fmt::format("an environment named '{}' is already registered", info.name),
                     "environment registry");
  }
  std::string name = info.name;
  entries_.emplace(std::move(name), std::move(info));
}

const EnvInfo& Registry::info(const std::string& name) const {
  const auto it = entries_.find(name);
  if (it == entries_.end()) {
    throw InputError(
        fmt::format("unknown environment '{}' (known: {})", name, fmt::join(names(), ", ")),
        "environment");
  }
  return it->second;
}

std::vector<std::string> Registry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, info] : entries_) out.push_back(name);
  return out;
}

std::unique_ptr<Environment> Registry::make(const std::string& name, const Params& params) const {
  const EnvInfo& entry = info(name);
  for (const auto& [key, value] : params) {
    bool known = false;
    std::vector<std::string> valid;
    for (const ParamSpec& spec : entry.params) {
      known = known || spec.name == key;
      valid.push_back(spec.name);
    }
    if (!known) {
      throw InputError(
          fmt::format("{} has no parameter '{}' (it takes: {})", name, key, fmt::join(valid, ", ")),
          name + "." + key);
    }
  }
  return entry.make(params);
}

void Environment::sampleAction(Rng& rng, std::span<double> action) const {
  const ActionSpace space = actionSpace();
  if (space.continuous()) {
    for (std::size_t i = 0; i < space.components; ++i) {
      action[i] = rng.uniform(space.low[i], space.high[i]);
    }
  } else {
    action[0] = static_cast<double>(rng.below(static_cast<std::uint64_t>(space.choices)));
  }
}

}  // namespace gpfd::env
