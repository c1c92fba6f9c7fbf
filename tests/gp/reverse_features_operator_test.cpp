// A GP operator added from outside the library: the function below and its one registration line
// are all it takes (docs/architecture.md, "Where a change goes"). Its weight is then the config
// key gp.operators.reverse_features; its default weight 0 leaves every other run unchanged.
#include <gtest/gtest.h>

#include <algorithm>

#include "gpfd/gp/evolution.hpp"
#include "gpfd/gp/operator_registry.hpp"
#include "gpfd/run/experiment_config.hpp"

namespace gpfd::gp {
namespace {

// The parent's features in reverse order (within the limits whenever the parent is).
expr::Genome reverseFeatures(Rng&, const expr::Genome& parent, const SearchSpace&) {
  expr::Genome child;
  for (std::size_t k = parent.featureCount(); k > 0; --k) child.addFeature(parent.feature(k - 1));
  return child;
}

// The registration line.
const bool kRegistered =
    (OperatorRegistry::global().add({"reverse_features", 0.0, reverseFeatures}), true);

std::size_t indexOf(const std::string& name) {
  const auto names = OperatorRegistry::global().names();
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

TEST(ReverseFeaturesOperator, IsRegisteredAfterTheBuiltInsWithNoWeight) {
  ASSERT_TRUE(kRegistered);
  const auto& operators = OperatorRegistry::global().operators();
  const std::size_t at = indexOf("reverse_features");
  ASSERT_LT(at, operators.size());
  EXPECT_GE(at, 5u);
  EXPECT_EQ(operators[at].parents(), 1);
  EXPECT_EQ(operatorProbabilities(GpConfig{})[at], 0.0);
}

TEST(ReverseFeaturesOperator, AloneItMakesEveryChild) {
  GpConfig config;
  config.population = 30;
  config.generations = 2;
  for (const auto& o : OperatorRegistry::global().operators()) config.operatorWeights[o.name] = 0.0;
  config.operatorWeights["reverse_features"] = 1.0;
  SearchSpace space;
  space.primitives = expr::PrimitiveSet::named("control");
  space.variableCount = 2;
  space.limits = {1, 5, 6, 30};
  SerialEvaluator evaluator([](const expr::Genome& g, Rng&) { return -double(g.size()); });
  Evolution evolution(config, space, evaluator);
  evolution.initialize();
  const auto first = evolution.population();
  evolution.step();
  const auto& counts = evolution.operatorCounts();
  for (std::size_t o = 0; o < counts.size(); ++o) {
    EXPECT_EQ(counts[o] > 0, o == indexOf("reverse_features")) << o;
  }
  Rng unused(0);
  for (const auto& child : evolution.population()) {
    const auto reversed = reverseFeatures(unused, child.genome, space);
    const bool fromFirst = std::any_of(first.begin(), first.end(), [&](const Individual& p) {
      return p.genome == child.genome || p.genome == reversed;
    });
    EXPECT_TRUE(fromFirst);
  }
}

TEST(ReverseFeaturesOperator, ItsWeightIsAConfigKey) {
  const auto config =
      run::parseExperimentConfig("[gp.operators]\nreverse_features = 2.5\n", "test.toml");
  EXPECT_EQ(config.gp.operatorWeights.at("reverse_features"), 2.5);
  const auto text = run::formatExperimentConfig(run::ExperimentConfig{});
  EXPECT_NE(text.find("reverse_features = 0.0"), std::string::npos) << text;
}

}  // namespace
}  // namespace gpfd::gp
