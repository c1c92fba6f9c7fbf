// The table of variation operators: the paper's five in a fixed order, their probabilities from
// the weights (bit for bit the rates of earlier versions), and refusals of bad weights and entries.
#include "gpfd/gp/operator_registry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gpfd/gp/evolution.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::gp {
namespace {

const std::vector<std::string> kPapers{"subtree_crossover", "feature_list_crossover",
                                       "node_mutation", "tree_mutation", "shrinkage"};

TEST(OperatorRegistry, ThePapersFiveComeFirstInAFixedOrder) {
  const auto& operators = OperatorRegistry::global().operators();
  ASSERT_GE(operators.size(), kPapers.size());
  for (std::size_t o = 0; o < kPapers.size(); ++o) {
    EXPECT_EQ(operators[o].name, kPapers[o]);
    EXPECT_EQ(operators[o].parents(), o < 2 ? 2 : 1) << kPapers[o];
  }
}

// The probabilities as earlier versions computed them from crossover, list_crossover_share and the
// three mutation weights, to the last bit (the same random draws).
std::vector<double> earlierProbabilities(double crossover, double listShare) {
  const double mutation = 1.0 - crossover;
  const double weights = 2.0 + 1.0 + 1.0;
  return {crossover * (1.0 - listShare), crossover * listShare, mutation * 2.0 / weights,
          mutation * 1.0 / weights, mutation * 1.0 / weights};
}

TEST(OperatorRegistry, DefaultProbabilitiesAreThePapersBitForBit) {
  const auto p = operatorProbabilities(GpConfig{});
  const auto expected = earlierProbabilities(0.7, 1.0 / 6.0);
  for (std::size_t o = 0; o < expected.size(); ++o) EXPECT_EQ(p[o], expected[o]) << kPapers[o];
  EXPECT_DOUBLE_EQ(crossoverProbability(GpConfig{}), 0.7);
}

TEST(OperatorRegistry, ProbabilitiesAreWeightsOverTheirSum) {
  GpConfig config;
  config.operatorWeights = {{"subtree_crossover", 2.0},
                            {"feature_list_crossover", 0.0},
                            {"node_mutation", 1.0},
                            {"tree_mutation", 1.0},
                            {"shrinkage", 0.0}};
  const auto p = operatorProbabilities(config);
  const std::vector<double> expected{0.5, 0.0, 0.25, 0.25, 0.0};
  for (std::size_t o = 0; o < expected.size(); ++o) EXPECT_EQ(p[o], expected[o]) << kPapers[o];
  EXPECT_EQ(crossoverProbability(config), 0.5);
  // An operator left out keeps its default weight.
  config.operatorWeights = {{"shrinkage", 0.0}};
  EXPECT_EQ(operatorProbabilities(config)[4], 0.0);
  EXPECT_GT(operatorProbabilities(config)[3], 0.0);
}

// validate's error for `weights`: its where ("" when it passes).
std::string refusal(std::map<std::string, double> weights) {
  GpConfig config;
  config.operatorWeights = std::move(weights);
  try {
    validate(config);
  } catch (const InputError& e) {
    return e.where() + ": " + e.what();
  }
  return "";
}

TEST(OperatorRegistry, BadWeightsAreRefused) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(refusal({{"shrinkage", 0.5}}), "");
  EXPECT_NE(refusal({{"shrinkage", -0.5}}).find("gp.operators.shrinkage: "), std::string::npos);
  EXPECT_NE(refusal({{"node_mutation", inf}}).find("gp.operators.node_mutation: "),
            std::string::npos);
  EXPECT_NE(refusal({{"node_mutation", std::nan("")}}).find("non-negative"), std::string::npos);
  EXPECT_NE(refusal({{"shrinkge", 1.0}}).find("unknown operator 'shrinkge'"), std::string::npos);
  std::map<std::string, double> zero;
  for (const auto& o : OperatorRegistry::global().operators()) zero[o.name] = 0.0;
  EXPECT_NE(refusal(zero).find("gp.operators: "), std::string::npos);
  EXPECT_NE(refusal(zero).find("must not all be zero"), std::string::npos);
  const double big = std::numeric_limits<double>::max();
  EXPECT_NE(refusal({{"subtree_crossover", big}, {"shrinkage", big}}).find("finite"),
            std::string::npos);
}

TEST(OperatorRegistry, AddRefusesIncompleteOrTakenEntries) {
  OperatorRegistry registry;
  const Mutation keep = [](Rng&, const expr::Genome& g, const SearchSpace&) { return g; };
  registry.add({"keep", 1.0, keep});
  EXPECT_EQ(registry.names(), std::vector<std::string>{"keep"});
  EXPECT_THROW(registry.add({"keep", 1.0, keep}), InputError);
  EXPECT_THROW(registry.add({"", 1.0, keep}), InputError);
  EXPECT_THROW(registry.add({"a.b", 1.0, keep}), InputError);
  EXPECT_THROW(registry.add({"none", 1.0, Mutation{}}), InputError);
  EXPECT_THROW(registry.add({"negative", -1.0, keep}), InputError);
  EXPECT_THROW(registry.add({"nan", std::nan(""), keep}), InputError);
  EXPECT_EQ(registry.names().size(), 1u);
}

}  // namespace
}  // namespace gpfd::gp
