// gp: the variation operators as an open table. Each has a name (its key in the config table
// gp.operators), one or two parents, a default weight and its function. Evolution draws one
// operator per child with probability weight / total weight, trying the operators in
// registration order: the paper's five first, in a fixed order, then any added later (a test, a
// plug-in) in the order they were added. The order and the weights decide the random draws.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "gpfd/gp/operators.hpp"

namespace gpfd::gp {

// One parent in, one child out.
using Mutation = std::function<expr::Genome(Rng&, const expr::Genome&, const SearchSpace&)>;
// Two parents in, two children out.
using Crossover =
    std::function<Offspring(Rng&, const expr::Genome&, const expr::Genome&, const SearchSpace&)>;

struct OperatorInfo {
  std::string name;  // Letters, digits and '_': a TOML key.
  // The weight when a config sets none. A new operator's 0 leaves every existing run unchanged.
  double defaultWeight = 0.0;
  std::variant<Mutation, Crossover> apply;

  int parents() const { return std::holds_alternative<Crossover>(apply) ? 2 : 1; }
};

class OperatorRegistry {
 public:
  // The one registry, holding the built-in operators from its first use.
  static OperatorRegistry& global();

  // Appends an operator. InputError when the name is empty, not a key, or taken, the function is
  // missing, or the default weight is negative or not finite.
  void add(OperatorInfo info);
  // In registration order.
  const std::vector<OperatorInfo>& operators() const { return operators_; }
  std::vector<std::string> names() const;
  bool contains(const std::string& name) const;

 private:
  std::vector<OperatorInfo> operators_;
};

// The weight of each of `operators`, in their order: the config's (`weights`, by name) or the
// operator's default.
std::vector<double> resolvedWeights(const std::map<std::string, double>& weights,
                                    const std::vector<OperatorInfo>& operators);

}  // namespace gpfd::gp
