// `--param k=v` handling shared by the commands: splitting, and routing a key to the environment
// (when it is one of its parameters) or to the learner.
#pragma once

#include <fmt/format.h>

#include <string>

#include "gpfd/env/environment.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::app {

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

inline bool isEnvParam(const env::EnvInfo& info, const std::string& key) {
  for (const auto& spec : info.params) {
    if (spec.name == key) return true;
  }
  return false;
}

}  // namespace gpfd::app
