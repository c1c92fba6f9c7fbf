#include <fmt/format.h>

#include <typeinfo>

#include "gpfd/env/acrobot.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/env/swimmer.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/util/error.hpp"
#include "twins.hpp"

namespace gpfd::env {
namespace {

// The built-in environments: one line each.
void addBuiltIns(Registry& registry) {
  registry.add(Acrobot::info());
  registry.add(CartPole::info());
  registry.add(Swimmer::info());
  registry.add(Tetris::info());
  // The twins of Gymnasium's classic-control tasks, under Gymnasium's ids.
  for (const auto make : {twin::cartPoleTwin, twin::acrobotTwin, twin::pendulumTwin,
                          twin::mountainCarTwin, twin::mountainCarContinuousTwin}) {
    registry.add(make());
  }
}

}  // namespace

Registry& Registry::global() { return instance<Registry>(addBuiltIns); }

void Registry::add(EnvInfo info) {
  if (!info.make) throw InputError("an environment needs a factory", "environment registry");
  if (info.batch.available && !info.batch.make) {
    throw InputError(fmt::format("environment '{}': a batched form needs its maker", info.name),
                     "environment registry");
  }
  NamedRegistry::add(std::move(info));
}

std::unique_ptr<Environment> Registry::make(const std::string& name, const Params& params) const {
  const EnvInfo& entry = info(name);
  checkParamNames(name, paramNames(entry.params), params);
  return entry.make(params);
}

std::unique_ptr<Environment> Environment::freshCopy() const {
  if (Registry::global().find(name()) == nullptr) return nullptr;
  std::unique_ptr<Environment> copy;
  try {
    copy = Registry::global().make(name(), params());
  } catch (const InputError&) {
    return nullptr;  // Another environment's parameters under a registered name.
  }
  const Environment& made = *copy;
  return typeid(made) == typeid(*this) ? std::move(copy) : nullptr;
}

void Environment::sampleAction(Rng& rng, std::span<double> action) const {
  const ActionSpace space = actionSpace();
  if (space.continuous()) {
    for (std::size_t i = 0; i < space.components; ++i) {
      action[i] = rng.uniform(space.low[i], space.high[i]);
    }
  } else {
    action[0] = static_cast<double>(rng.below(static_cast<std::uint64_t>(space.choices.at(0))));
  }
}

}  // namespace gpfd::env
