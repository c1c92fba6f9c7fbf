#include "gpfd/gp/operator_registry.hpp"

#include <algorithm>
#include <cmath>

#include "gpfd/util/error.hpp"

namespace gpfd::gp {
namespace {

// The paper's five operators (section 4) with its rates as default weights: crossover 0.7, of
// which 1/6 feature-list crossover; the other 0.3 to node mutation, tree mutation and shrinkage
// as 2 : 1 : 1. One line each; the order is part of every run's random draws.
void addBuiltIns(OperatorRegistry& registry) {
  registry.add({"subtree_crossover", 0.7 * (1.0 - 1.0 / 6.0), subtreeCrossover});
  registry.add({"feature_list_crossover", 0.7 * (1.0 / 6.0), featureListCrossover});
  registry.add({"node_mutation", (1.0 - 0.7) * 2.0 / 4.0, nodeMutation});
  registry.add({"tree_mutation", (1.0 - 0.7) * 1.0 / 4.0, treeMutation});
  registry.add({"shrinkage", (1.0 - 0.7) * 1.0 / 4.0, shrinkage});
}

bool isKey(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

}  // namespace

OperatorRegistry& OperatorRegistry::global() {
  static OperatorRegistry registry = [] {
    OperatorRegistry r;
    addBuiltIns(r);
    return r;
  }();
  return registry;
}

void OperatorRegistry::add(OperatorInfo info) {
  const std::string where = "operator registry";
  if (!isKey(info.name)) {
    throw InputError("an operator needs a name of letters, digits and '_', not '" + info.name + "'",
                     where);
  }
  if (contains(info.name)) {
    throw InputError("operator '" + info.name + "' is already registered", where);
  }
  const bool hasFunction =
      std::visit([](const auto& f) { return static_cast<bool>(f); }, info.apply);
  if (!hasFunction) throw InputError("operator '" + info.name + "' has no function", where);
  if (!std::isfinite(info.defaultWeight) || info.defaultWeight < 0) {
    throw InputError("operator '" + info.name + "' needs a finite, non-negative default weight",
                     where);
  }
  operators_.push_back(std::move(info));
}

std::vector<std::string> OperatorRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& o : operators_) out.push_back(o.name);
  return out;
}

bool OperatorRegistry::contains(const std::string& name) const {
  return std::any_of(operators_.begin(), operators_.end(),
                     [&](const OperatorInfo& o) { return o.name == name; });
}

std::vector<double> resolvedWeights(const std::map<std::string, double>& weights,
                                    const std::vector<OperatorInfo>& operators) {
  std::vector<double> out;
  for (const auto& o : operators) {
    const auto it = weights.find(o.name);
    out.push_back(it == weights.end() ? o.defaultWeight : it->second);
  }
  return out;
}

}  // namespace gpfd::gp
