// service: `k=v` parameters (`--param`, Python's params=): splitting, and routing a key to the
// environment (when it is one of its parameters) or to the learner.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::service {

struct KeyValue {
  std::string key, value;
};

// "k=v" -> {k, v}; InputError at `where` for text without a key and '='.
inline KeyValue splitKeyValue(const std::string& text, const std::string& where) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(fmt::format("expected k=v, got '{}'", text), where);
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

struct RoutedParams {
  Params env, learner;
};

// Splits each "k=v" (InputError at `where`) and sends it to the environment when `info` declares
// the key, else to the learner.
inline RoutedParams routeParams(const std::vector<std::string>& assignments,
                                const env::EnvInfo& info, const std::string& where) {
  const auto envNames = paramNames(info.params);
  RoutedParams routed;
  for (const auto& text : assignments) {
    auto [key, value] = splitKeyValue(text, where);
    const bool forEnv = std::find(envNames.begin(), envNames.end(), key) != envNames.end();
    (forEnv ? routed.env : routed.learner)[key] = std::move(value);
  }
  return routed;
}

// Runs `f`; an InputError from it is reported at `where` instead of its own place.
template <typename F>
decltype(auto) reportedAt(const std::string& where, F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(e.what(), where);
  }
}

}  // namespace gpfd::service
