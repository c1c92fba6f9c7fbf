#include "gpfd/run/assessment.hpp"

#include <gtest/gtest.h>

#include "gpfd/expr/parse.hpp"

namespace gpfd::run {
namespace {

ExperimentConfig smallConfig() {
  ExperimentConfig c;
  c.env = "cartpole";
  c.envParams = {{"max_steps", "100"}};
  c.assessParams = {{"updates", "3"}, {"episodes", "4"}};
  c.assessRuns = 3;
  return c;
}

TEST(Assessment, SameResultWithOneAndTwoThreadsAndAreasAreCurveMeans) {
  const LearningTask task(smallConfig(), LearningTask::Budget::Assessment);
  expr::Genome sincos;
  sincos.addFeature(expr::parseInfix("sin(th)", task.stateNames()));
  sincos.addFeature(expr::parseInfix("dth * 2", task.stateNames()));
  const std::vector<FeatureSet> sets{{"original", TrialFeatures::original()},
                                     {"mine", TrialFeatures::ofGenome(sincos, true)}};
  ThreadTrialRunner oneThread(1), twoThreads(2);
  const auto one = runAssessment(task, sets, 3, 7, oneThread);
  const auto two = runAssessment(task, sets, 3, 7, twoThreads);
  ASSERT_EQ(one.curves.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(one.finals(s), two.finals(s));
    EXPECT_EQ(one.areas(s), two.areas(s));
    ASSERT_EQ(one.curves[s].size(), 3u);
    const auto& points = one.curves[s][0].points;
    ASSERT_EQ(points.size(), 4u);  // Row 0 and 3 updates.
    double sum = 0;
    for (const auto& p : points) sum += p.meanReturn;
    EXPECT_DOUBLE_EQ(one.areas(s)[0], sum / 4);
  }
  // Runs are independent: different seeds per run.
  EXPECT_NE(one.finals(0)[0], one.finals(0)[1]);
  const auto summary = summarizeAssessment(one, 0);
  EXPECT_EQ(summary[0].vsBaseline.welchP, 1.0);
  EXPECT_EQ(summary[1].name, "mine");
}

}  // namespace
}  // namespace gpfd::run
