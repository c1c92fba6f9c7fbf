#include "gpfd/run/redundancy.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "gpfd/env/environment.hpp"
#include "gpfd/expr/parse.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/run/learning_task.hpp"

namespace gpfd::run {
namespace {

const expr::VariableNames kNames{"x", "dx", "th", "dth"};

std::shared_ptr<const FeatureSample> cartPoleSample() {
  auto env = env::Registry::global().make("cartpole");
  return std::make_shared<const FeatureSample>(sampleVisitedStates(*env, 256, 7), 4);
}

expr::Genome genome(const std::vector<std::string>& features) {
  expr::Genome g;
  for (const auto& f : features) g.addFeature(expr::parseInfix(f, kNames));
  return g;
}

std::vector<std::string> infix(const expr::Genome& g) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < g.featureCount(); ++k)
    out.push_back(expr::toInfix(g.feature(k), kNames));
  return out;
}

TEST(StateSample, IsDeterministicFiniteAndVaried) {
  auto env = env::Registry::global().make("cartpole");
  const auto a = sampleVisitedStates(*env, 100, 3), b = sampleVisitedStates(*env, 100, 3);
  ASSERT_EQ(a.size(), 400u);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, sampleVisitedStates(*env, 100, 4));
  for (const double v : a) EXPECT_TRUE(std::isfinite(v));
  const FeatureSample sample(a, 4);
  const auto th = sample.variable(2);
  EXPECT_NE(*std::min_element(th.begin(), th.end()), *std::max_element(th.begin(), th.end()));
}

TEST(Redundancy, DropsRepeatsLinearCombinationsAndConstants) {
  const RedundancyFilter filter(cartPoleSample(), false, 1);
  EXPECT_EQ(infix(filter(genome({"dth + th", "th", "dth + th", "dth", "2 * th - 3", "1.5"}))),
            (std::vector<std::string>{"dth + th", "th"}));
}

TEST(Redundancy, AGenomeVariesWhenOneOfItsFeaturesDoes) {
  const auto sample = cartPoleSample();
  EXPECT_FALSE(variesOnSample(genome({"1.5"}), *sample));
  EXPECT_FALSE(variesOnSample(genome({"th - th + 2", "cos(0)"}), *sample));
  EXPECT_FALSE(variesOnSample(genome({"sqrt(0 - 1)"}), *sample));  // Non-finite everywhere.
  EXPECT_TRUE(variesOnSample(genome({"2", "th * dth"}), *sample));
  EXPECT_TRUE(variesOnSample(genome({"sin(x)"}), *sample));
}

TEST(Redundancy, KeepsNonlinearFeaturesEvenWhenClose) {
  // sin(th) and th differ by about th^3 / 6 on cart-pole's small angles: not redundant.
  const RedundancyFilter filter(cartPoleSample(), false, 1);
  const auto kept = filter(genome({"th", "sin(th)", "th * th", "x * dx"}));
  EXPECT_EQ(kept.featureCount(), 4u);
}

TEST(Redundancy, NearCopiesGoWhenTheSpanExplainsEnoughOfTheirVariance) {
  // sin(sin(th)) beside sin(th) (cart-pole's small angles) and 3 * dth + x / 1000 beside dth:
  // exact dependence keeps both, genome.redundant_r2 = 0.998 drops the near copies.
  const auto set = genome({"sin(th)", "sin(sin(th))", "dth", "3 * dth + x / 1000", "th * dth"});
  EXPECT_EQ(RedundancyFilter(cartPoleSample(), false, 1)(set).featureCount(), 5u);
  EXPECT_EQ(infix(RedundancyFilter(cartPoleSample(), false, 1, 0.998)(set)),
            (std::vector<std::string>{"sin(th)", "dth", "th * dth"}));
}

TEST(Redundancy, WithTheOriginalVariablesTheirCombinationsAreRedundant) {
  const RedundancyFilter filter(cartPoleSample(), true, 1);
  EXPECT_EQ(infix(filter(genome({"x - dth", "sin(th)", "dx"}))),
            (std::vector<std::string>{"sin(th)"}));
}

TEST(Redundancy, KeepsTheMinimumNumberOfFeatures) {
  const RedundancyFilter one(cartPoleSample(), false, 1);
  EXPECT_EQ(infix(one(genome({"1.5", "2 * 1.5"}))), (std::vector<std::string>{"1.5"}));
  const RedundancyFilter two(cartPoleSample(), false, 2);
  EXPECT_EQ(infix(two(genome({"x", "2 * x", "3 * x"}))), (std::vector<std::string>{"x", "2 * x"}));
}

TEST(Redundancy, BesideTheOriginalVariablesPlaceholdersFillTheMinimum) {
  // A copy of an original variable would double that direction's Rprop steps: the constant 0
  // takes its place, and the feature map leaves it out.
  const RedundancyFilter one(cartPoleSample(), true, 1);
  const auto none = one(genome({"x", "2 * dx - th"}));
  EXPECT_EQ(infix(none), (std::vector<std::string>{"0"}));
  EXPECT_TRUE(onlyPlaceholders(none));
  EXPECT_EQ(withoutPlaceholders(none).featureCount(), 0u);
  const RedundancyFilter two(cartPoleSample(), true, 2);
  const auto some = two(genome({"x", "sin(th)", "dx"}));
  EXPECT_EQ(infix(some), (std::vector<std::string>{"sin(th)", "0"}));
  EXPECT_FALSE(onlyPlaceholders(some));
  EXPECT_EQ(infix(withoutPlaceholders(some)), (std::vector<std::string>{"sin(th)"}));
  EXPECT_EQ(infix(one(none)), (std::vector<std::string>{"0"}));  // Idempotent.
}

TEST(Redundancy, TheFeatureMapLeavesPlaceholdersOut) {
  const auto alone = genomeFeatureMap(genome({"0"}), 4, true);
  EXPECT_TRUE(alone->isIdentity());  // The original variables, once.
  const auto some = genomeFeatureMap(genome({"sin(th)", "0"}), 4, true);
  ASSERT_EQ(some->outputDim(), 5u);
  const double state[4] = {0.1, -0.2, 0.3, 0.4};
  double features[5];
  some->evaluate(state, features);
  EXPECT_DOUBLE_EQ(features[0], std::sin(0.3));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(features[1 + i], state[i]);
  // Without the original variables the constant 0 is an ordinary (useless) feature.
  EXPECT_EQ(genomeFeatureMap(genome({"sin(th)", "0"}), 4, false)->outputDim(), 2u);
}

TEST(Normalise, GivesZeroMeanAndUnitDeviationOnTheSample) {
  const auto sample = cartPoleSample();
  const auto scaled = normaliseFeatures(genome({"3 * th + 1", "dx * dx", "2"}), *sample);
  for (std::size_t k = 0; k < 2; ++k) {
    const auto values = sample->column(scaled, k);
    double mean = 0.0, squares = 0.0;
    for (const double v : values) mean += v / static_cast<double>(values.size());
    for (const double v : values) squares += (v - mean) * (v - mean);
    EXPECT_NEAR(mean, 0.0, 1e-12);
    EXPECT_NEAR(std::sqrt(squares / static_cast<double>(values.size())), 1.0, 1e-12);
  }
  // A constant is left as it is.
  EXPECT_EQ(expr::toInfix(scaled.feature(2), kNames), "2");
}

}  // namespace
}  // namespace gpfd::run
