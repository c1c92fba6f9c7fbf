// The trials of a fitness evaluation (and the seeds of validation, re-measurement and assessment)
// trained together through Learner::trainRuns give, bit for bit, what training each alone gives:
// the same curves, trial fitness, validation scores and assessment curves as the one-by-one path.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../rl/same_curves.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/assessment.hpp"
#include "gpfd/run/experiment_config.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/validation.hpp"

namespace gpfd::run {
namespace {

using rl::testing::expectSameCurves;
using rl::testing::sameBits;

// A quick config's trial (its environment, learner settings and trials), shortened to `updates`.
ExperimentConfig quickConfig(const std::string& name, const std::string& updates) {
  ExperimentConfig config =
      loadExperimentConfig(std::string(GPFD_SOURCE_DIR) + "/configs/" + name + "-quick.toml");
  config.learnerParams["updates"] = updates;
  return config;
}

expr::Genome genomeOf(const LearningTask& task, const std::string& text) {
  return expr::parseFeaturesFile(text, "test", task.stateNames(), task.config().env).genome;
}

// trialFitness as it was before the trials were trained together: one after another.
double fitnessOneByOne(const LearningTask& task, const expr::Genome& genome, Rng& rng) {
  const auto map = task.featureMap(genome);
  const std::uint64_t base = rng();
  double sum = 0.0;
  for (int t = 0; t < task.config().trials; ++t) {
    Rng trialRng(deriveSeed(base, t));
    const double s = task.score(task.train(*map, trialRng));
    if (!std::isfinite(s)) return -INFINITY;
    sum += s;
  }
  return sum / task.config().trials;
}

struct Case {
  std::string config;
  std::string features;
};

TEST(TrialsTogether, FitnessAndCurvesEqualTheOneByOnePath) {
  const std::vector<Case> cases{
      {"cartpole", "x\nsin(th) * dth\ncos(th)\ndx - th\n"},
      {"acrobot", "sin(th1)\ncos(th2)\ndth1 + dth2\ndth2 * cos(th1 - th2)\n"},
      {"swimmer3", "dGx\nsin(th1) + dth2\nth2 - th3\n"},
      {"swimmer5", "dGx\nsin(th1 - th2) * dth3\n"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.config);
    for (const bool lockstep : {true, false}) {
      ExperimentConfig config = quickConfig(c.config, "5");
      config.learnerParams["lockstep"] = lockstep ? "true" : "false";
      const LearningTask task(config, LearningTask::Budget::Trial);
      const expr::Genome genome = genomeOf(task, c.features);
      for (const std::uint64_t seed : {7u, 8u}) {
        Rng a(seed), b(seed);
        const double together = trialFitness(task, genome, a);
        const double alone = fitnessOneByOne(task, genome, b);
        EXPECT_TRUE(std::isfinite(together));
        EXPECT_TRUE(sameBits(together, alone)) << together << " vs " << alone;
        EXPECT_EQ(a(), b()) << "the caller's engine advanced differently";
      }
      const auto map = task.featureMap(genome);
      std::vector<Rng> rngs{Rng(11), Rng(12), Rng(13)};
      const auto curves = task.trainRuns(*map, rngs);
      ASSERT_EQ(curves.size(), 3u);
      for (std::size_t k = 0; k < 3; ++k) {
        Rng alone(11 + k);
        expectSameCurves(curves[k], task.train(*map, alone));
        EXPECT_EQ(rngs[k](), alone());
      }
    }
  }
}

// Every run's rows reach the progress callback with the run's index, in order: played together
// (pg with lockstep) and one after another (pg without, and lambda-PI through Learner's default).
TEST(TrialsTogether, ProgressSeesEveryRunsRowsInOrder) {
  struct Setting {
    std::string env;
    env::Params envParams;
    std::string learner;
    Params params;
  };
  const std::vector<Setting> settings{
      {"cartpole", {{"max_steps", "100"}}, "pg", {{"updates", "4"}, {"lockstep", "true"}}},
      {"cartpole", {{"max_steps", "100"}}, "pg", {{"updates", "4"}, {"lockstep", "false"}}},
      {"tetris",
       {{"rows", "8"}, {"cols", "6"}},
       "lpi",
       {{"iterations", "2"}, {"games", "3"}, {"max_moves", "50"}}}};
  for (const Setting& s : settings) {
    SCOPED_TRACE(s.learner + " on " + s.env);
    const auto learner = rl::LearnerRegistry::global().make(s.learner, s.params);
    const auto makeEnv = [&] { return env::Registry::global().make(s.env, s.envParams); };
    const features::RawFeatureMap map(makeEnv()->stateDim());
    std::vector<Rng> rngs{Rng(5), Rng(6), Rng(7)};
    std::vector<std::vector<rl::CurvePoint>> seen(3);
    const auto curves =
        learner->trainRuns(makeEnv, map, rngs, [&](std::size_t run, const rl::CurvePoint& point) {
          ASSERT_LT(run, 3u);
          seen[run].push_back(point);
        });
    ASSERT_EQ(curves.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
      Rng alone(5 + k);
      const auto env = makeEnv();
      expectSameCurves(curves[k], learner->train(*env, map, alone));
      EXPECT_EQ(rngs[k](), alone());
      EXPECT_EQ(curves[k].points.size(), s.learner == "pg" ? 5u : 3u);
      ASSERT_EQ(seen[k].size(), curves[k].points.size());
      for (std::size_t i = 0; i < seen[k].size(); ++i) {
        EXPECT_EQ(seen[k][i].update, curves[k].points[i].update);
        EXPECT_TRUE(sameBits(seen[k][i].meanReturn, curves[k].points[i].meanReturn));
      }
    }
  }
}

// Validation and re-measurement scores, and assessment curves, equal training each seed alone.
TEST(TrialsTogether, ValidationAndAssessmentEqualTheOneByOnePath) {
  ExperimentConfig config = quickConfig("acrobot", "3");
  config.envParams["max_steps"] = "300";
  config.validation.seeds = 7;  // Groups of 5 and 2 runs, or smaller on many threads.
  config.assessParams = {{"updates", "4"}};
  ThreadTrialRunner runner(2);
  const Validator validator(config, runner);
  const LearningTask& task = validator.task();
  const expr::Genome genome = genomeOf(task, "sin(th1)\ndth1 * cos(th2)\n");
  const std::vector<std::shared_ptr<const features::FeatureMap>> maps{
      task.featureMap(genome), std::make_shared<const features::RawFeatureMap>(task.stateDim())};
  const auto scores = validator.score(std::vector<const expr::Genome*>{&genome, nullptr});
  ASSERT_EQ(scores.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    ASSERT_EQ(scores[s].size(), 7u);
    for (std::size_t m = 0; m < 7; ++m) {
      Rng rng(deriveSeed(config.seed, Validator::kValidationStream, m));
      const double alone = task.score(task.train(*maps[s], rng));
      EXPECT_TRUE(std::isfinite(alone));
      EXPECT_TRUE(sameBits(scores[s][m], alone)) << s << " " << m;
    }
  }
  const LearningTask assessTask(config, LearningTask::Budget::Assessment);
  const std::vector<FeatureSet> sets{
      {"mine", TrialFeatures::ofGenome(task.prepared(genome), config.withOriginal)},
      {"original", TrialFeatures::original()}};
  std::atomic<long> progress{0};
  ThreadTrialRunner oneThread(1);
  const auto result = runAssessment(assessTask, sets, 6, 9, oneThread, &progress);
  EXPECT_EQ(progress.load(), 12);
  for (std::size_t s = 0; s < 2; ++s) {
    for (std::size_t r = 0; r < 6; ++r) {
      Rng rng(deriveSeed(9, s, r));
      EXPECT_EQ(result.curves[s][r].points.size(), 5u);
      expectSameCurves(result.curves[s][r], assessTask.train(*maps[s], rng));
    }
  }
}

}  // namespace
}  // namespace gpfd::run
