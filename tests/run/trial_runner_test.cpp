// The seam through which validation, confirmation and assessment train their runs
// (gpfd/run/trial_runner.hpp): a run hands every such batch to the runner it is given, and any
// runner gives the same results.
#include "gpfd/run/trial_runner.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <mutex>

#include "cli_helpers.hpp"
#include "gpfd/expr/parse.hpp"
#include "gpfd/run/discovery.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::testing {
namespace {

using Budget = run::LearningTask::Budget;

// Trains on one thread and notes the budget and size of every batch it is given.
class RecordingRunner final : public run::TrialRunner {
 public:
  std::vector<std::vector<rl::LearningCurve>> run(
      const run::LearningTask& task, const run::TrialBatch& batch,
      const std::function<void(std::size_t)>& done) override {
    {
      const std::lock_guard lock(mutex_);
      batches.emplace_back(task.budget(), batch.sets.size() * batch.runs());
    }
    return run::ThreadTrialRunner(1).run(task, batch, done);
  }
  std::vector<std::pair<Budget, std::size_t>> batches;

 private:
  std::mutex mutex_;
};

service::EvolveRequest request(const std::string& out, int threads) {
  service::EvolveRequest r;
  r.config = tinyEvolveConfig("runner", 4);
  r.overrides = {"gp.generations=2", "validation.confirm_params.updates=5"};
  r.out = {out, false, "--out"};
  r.threads = threads;
  return r;
}

// What a finished run wrote, but its timings.
std::string results(const std::string& dir) {
  return withoutSeconds(readText(dir + "/generations.csv")) + readText(dir + "/validation.csv") +
         readText(dir + "/confirmation.csv") + readText(dir + "/best.features") +
         readText(dir + "/front.csv");
}

TEST(TrialRunner, ValidationAndConfirmationRunOnTheRunnerGivenWithTheSameResults) {
  service::EvolveProgress quiet;
  const std::atomic<bool> stop{false};
  const auto plain = freshDir("runner-threads");
  ASSERT_TRUE(service::evolve(request(plain, 2), quiet, stop).finished);

  const auto given = freshDir("runner-given");
  auto withRunner = request(given, 2);
  const auto runner = std::make_shared<RecordingRunner>();
  withRunner.trialRunner = runner;
  ASSERT_TRUE(service::evolve(withRunner, quiet, stop).finished);

  const auto config = service::loadConfig(withRunner.config, withRunner.overrides);
  bool validation = false, confirmation = false;
  std::size_t confirmed = 0;
  for (const auto& [budget, runs] : runner->batches) {
    validation |= budget == Budget::Validation;
    confirmation |= budget == Budget::Confirmation;
    if (budget == Budget::Confirmation) confirmed += runs;
  }
  EXPECT_TRUE(validation);
  EXPECT_TRUE(confirmation);
  EXPECT_GE(confirmed, static_cast<std::size_t>(config.validation.confirmSeeds) / 3);
  EXPECT_EQ(results(given), results(plain));
}

TEST(TrialRunner, OneAndTwoThreadsGiveTheSameCurves) {
  auto config = service::loadConfig("cartpole-quick", {"learner.params.updates=3"});
  const run::LearningTask task(config, Budget::Validation);
  expr::Genome genome;
  genome.addFeature(expr::parseInfix("sin(th) * dth", task.stateNames()));
  const run::TrialBatch batch{
      {run::TrialFeatures::original(), run::TrialFeatures::ofGenome(genome, true)},
      {{1, 2, 3}, {4, 5, 6}}};
  const auto one = run::ThreadTrialRunner(1).run(task, batch, {});
  const auto two = run::ThreadTrialRunner(2).run(task, batch, {});
  ASSERT_EQ(one.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    ASSERT_EQ(one[s].size(), 3u);
    for (std::size_t r = 0; r < 3; ++r) {
      Rng rng(batch.seeds[s][r]);
      const auto alone = task.train(*batch.sets[s].map(task), rng);
      ASSERT_EQ(one[s][r].points.size(), alone.points.size());
      for (std::size_t i = 0; i < alone.points.size(); ++i) {
        EXPECT_EQ(one[s][r].points[i].meanReturn, alone.points[i].meanReturn);
        EXPECT_EQ(two[s][r].points[i].meanReturn, alone.points[i].meanReturn);
      }
    }
  }
}

// The default results directory may be named for the environment; never a path.
TEST(TrialRunner, AResultsDirectoryNameIsAPlainName) {
  service::EvolveProgress quiet;
  const std::atomic<bool> stop{false};
  for (const std::string bad : {"..", "../escape", "a/b", ".hidden"}) {
    auto r = request("", 1);
    r.out = {std::nullopt, false, "--out"};
    r.outName = bad;
    EXPECT_THROW(service::evolve(r, quiet, stop), InputError) << bad;
  }
  EXPECT_FALSE(std::filesystem::exists("results/escape"));
}

}  // namespace
}  // namespace gpfd::testing
