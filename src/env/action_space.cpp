// env: what every environment's action space gives by default: the count of its discrete actions,
// all of them legal in every state, and an action kept as it is.
#include <fmt/format.h>

#include <algorithm>

#include "gpfd/env/environment.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

std::size_t ActionSpace::discreteActions() const {
  if (continuous()) return 0;
  std::size_t count = 1;
  for (const int c : choices) count *= static_cast<std::size_t>(c);
  return count;
}

void Environment::legalActionMask(std::span<std::uint8_t> mask) const {
  const std::size_t count = actionSpace().discreteActions();
  if (mask.size() != count) {
    throw InputError(
        fmt::format("{} has {} discrete actions, got a mask of {}", name(), count, mask.size()),
        name() + " action mask");
  }
  std::fill(mask.begin(), mask.end(), std::uint8_t{1});
}

void Environment::nearestLegalAction(std::span<const double> action,
                                     std::span<double> legal) const {
  std::copy(action.begin(), action.end(), legal.begin());
}

}  // namespace gpfd::env
