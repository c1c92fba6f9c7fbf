#include "gpfd/run/redundancy.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "gpfd/env/environment.hpp"
#include "gpfd/expr/parse.hpp"
#include "gpfd/expr/print.hpp"

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

TEST(Redundancy, KeepsNonlinearFeaturesEvenWhenClose) {
  // sin(th) and th differ by about th^3 / 6 on cart-pole's small angles: not redundant.
  const RedundancyFilter filter(cartPoleSample(), false, 1);
  const auto kept = filter(genome({"th", "sin(th)", "th * th", "x * dx"}));
  EXPECT_EQ(kept.featureCount(), 4u);
}

TEST(Redundancy, WithTheOriginalVariablesTheirCombinationsAreRedundant) {
  const RedundancyFilter filter(cartPoleSample(), true, 1);
  EXPECT_EQ(infix(filter(genome({"x - dth", "sin(th)", "dx"}))),
            (std::vector<std::string>{"sin(th)"}));
}

TEST(Redundancy, KeepsTheMinimumNumberOfFeatures) {
  const RedundancyFilter one(cartPoleSample(), true, 1);
  EXPECT_EQ(infix(one(genome({"x", "dx"}))), (std::vector<std::string>{"x"}));
  const RedundancyFilter two(cartPoleSample(), true, 2);
  EXPECT_EQ(infix(two(genome({"x", "dx", "th"}))), (std::vector<std::string>{"x", "dx"}));
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
