// util: what the environment and learner registries share: entries kept by unique name, found
// with errors that list the known names.
#pragma once

#include <fmt/format.h>

#include <map>
#include <string>
#include <vector>

#include "gpfd/util/error.hpp"

namespace gpfd {

// Info has a `std::string name`.
template <typename Info>
class NamedRegistry {
 public:
  // `kind` names an entry in errors ("environment", "learner").
  explicit NamedRegistry(std::string kind) : kind_(std::move(kind)) {}

  // Throws InputError when the name is empty or taken.
  void add(Info info) {
    if (info.name.empty()) throw InputError("a " + kind_ + " needs a name", kind_ + " registry");
    if (entries_.count(info.name)) {
      throw InputError(fmt::format("{} '{}' is already registered", kind_, info.name),
                       kind_ + " registry");
    }
    std::string name = info.name;
    entries_.emplace(std::move(name), std::move(info));
  }
  // Throws InputError naming the unknown entry and the known names.
  const Info& info(const std::string& name) const {
    const auto it = entries_.find(name);
    if (it == entries_.end()) {
      throw InputError(
          fmt::format("unknown {} '{}' (known: {})", kind_, name, fmt::join(names(), ", ")), kind_);
    }
    return it->second;
  }
  // The entry named `name`, or nullptr.
  const Info* find(const std::string& name) const {
    const auto it = entries_.find(name);
    return it == entries_.end() ? nullptr : &it->second;
  }
  // In alphabetical order.
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& [name, info] : entries_) out.push_back(name);
    return out;
  }

 protected:
  // The one instance of a derived registry, filled by `fill` on first use (its global()).
  template <typename Derived>
  static Derived& instance(void (*fill)(Derived&)) {
    static Derived registry = [fill] {
      Derived r;
      fill(r);
      return r;
    }();
    return registry;
  }

 private:
  std::string kind_;
  std::map<std::string, Info> entries_;
};

}  // namespace gpfd
