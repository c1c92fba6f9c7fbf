// The service layer's discovery request (gpfd/service/evolve.hpp): one writer per directory,
// features files that say what they are, and the text a run prints.
#include <gtest/gtest.h>

#include <filesystem>

#include "../run/cli_helpers.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/service/evolve_text.hpp"
#include "gpfd/util/directory_lock.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/version.hpp"

namespace gpfd::testing {
namespace {

// Stops the run after the first generation.
class StopAfterFirst final : public service::EvolveProgress {
 public:
  explicit StopAfterFirst(std::atomic<bool>& stop) : stop_(stop) {}
  void generationDone(const run::Discovery&, const run::GenerationRecord&,
                      const std::string&) override {
    stop_.store(true);
  }

 private:
  std::atomic<bool>& stop_;
};

service::EvolveRequest tinyRequest(const std::string& name, const std::string& out) {
  service::EvolveRequest request;
  request.config = tinyEvolveConfig(name, 5);
  request.out = {out, false, "--out"};
  request.threads = 1;
  return request;
}

TEST(EvolveService, ADirectoryLockedByAnotherWriterIsRefused) {
  const auto dir = freshDir("service-locked");
  const DirectoryLock other(dir, "results directory");
  service::EvolveProgress quiet;
  const std::atomic<bool> stop{false};
  try {
    service::evolve(tinyRequest("service-locked", dir), quiet, stop);
    FAIL() << "a locked directory was written into";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("another gpfd process"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/config.toml"));
}

TEST(EvolveService, ADirectoryHoldingOtherFilesNeedsForce) {
  const auto dir = freshDir("service-busy");
  std::filesystem::create_directories(dir);
  const auto mine = writeText("service-busy/notes.txt", "mine\n");
  service::EvolveProgress quiet;
  std::atomic<bool> stop{false};
  auto request = tinyRequest("service-busy", dir);
  EXPECT_THROW(service::evolve(request, quiet, stop), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir + "/config.toml"));
  request.out.force = true;
  StopAfterFirst stopper(stop);
  const auto result = service::evolve(request, stopper, stop);
  EXPECT_FALSE(result.finished);
  EXPECT_EQ(readText(mine), "mine\n");
  // A directory holding a run is never started over, forced or not.
  stop.store(false);
  EXPECT_THROW(service::evolve(request, quiet, stop), InputError);
}

// A run killed before it stored its config leaves only gpfd's own traces (an empty best/, a
// temporary file of an atomic write, the lock file): a plain restart into it is no overwrite.
TEST(EvolveService, ARunKilledBeforeItsConfigStartsAgainWithoutForce) {
  const auto dir = freshDir("service-killed-early");
  std::filesystem::create_directories(dir + "/best");
  const auto temporary = writeText("service-killed-early/config.toml.tmp.123456", "name = \"t");
  writeText("service-killed-early/.gpfd.lock", "123456\n");
  service::EvolveProgress quiet;
  std::atomic<bool> stop{false};
  StopAfterFirst stopper(stop);
  const auto result = service::evolve(tinyRequest("service-killed-early", dir), stopper, stop);
  EXPECT_FALSE(result.finished);
  EXPECT_TRUE(std::filesystem::exists(dir + "/config.toml"));
  EXPECT_FALSE(std::filesystem::exists(temporary));
  // A file of the user's in a subdirectory still needs force.
  const auto other = freshDir("service-killed-nested");
  std::filesystem::create_directories(other + "/best");
  writeText("service-killed-nested/best/mine.txt", "mine\n");
  stop.store(false);
  EXPECT_THROW(service::evolve(tinyRequest("service-killed-nested", other), quiet, stop),
               InputError);
}

// An interrupted run's features files hold the genome as the learner saw it (normalised here)
// and say that it is not validated.
TEST(EvolveService, AStoppedRunsFeaturesAreWhatTheLearnerSawAndSaySo) {
  const auto dir = freshDir("service-stopped");
  auto request = tinyRequest("service-stopped", dir);
  request.overrides = {"fitness.normalise=true"};
  std::atomic<bool> stop{false};
  StopAfterFirst stopper(stop);
  const auto result = service::evolve(request, stopper, stop);
  ASSERT_FALSE(result.finished);

  const auto config = service::loadConfig(request.config, request.overrides);
  const run::LearningTask task(config, run::LearningTask::Budget::Trial);
  auto resumed = run::Discovery::resume(
      {dir, 1, kVersion, "", {}, 1, {}, "", {}, 0.0, "", "", "", 0.0}, std::nullopt, std::nullopt);
  const auto& best = resumed->history().at(0).bestGenome;
  for (const std::string name : {"best.features", "best/generation-0000.features"}) {
    const auto file = expr::readFeaturesFile(dir + "/" + name);
    ASSERT_TRUE(file.meta.contains("status")) << name;
    EXPECT_TRUE(file.meta.at("status").starts_with("not validated")) << file.meta.at("status");
    EXPECT_TRUE(file.meta.contains("gp_fitness"));
    EXPECT_FALSE(file.meta.contains("fitness"));
  }
  // generation 0's file evaluates exactly as the learner's feature map of that genome.
  const auto file = expr::readFeaturesFile(dir + "/best/generation-0000.features");
  const jit::CompiledFeatureMap fromFile(file.genome, task.stateDim());
  const auto learner = task.featureMap(best);
  ASSERT_EQ(fromFile.outputDim(), learner->outputDim());
  const std::vector<std::vector<double>> states{
      {0.1, -0.2, 0.03, 0.5}, {-1.0, 0.7, -0.1, -0.3}, {2.0, 1.5, 0.2, 1.1}};
  for (const auto& s : states) {
    std::vector<double> a(learner->outputDim()), b(learner->outputDim());
    fromFile.evaluate(s.data(), a.data());
    learner->evaluate(s.data(), b.data());
    EXPECT_EQ(a, b);
  }
  // Without normalisation in the file (the raw genome, as before) the values differ.
  const jit::CompiledFeatureMap raw(best, task.stateDim());
  std::vector<double> a(raw.outputDim()), b(learner->outputDim());
  raw.evaluate(states[0].data(), a.data());
  learner->evaluate(states[0].data(), b.data());
  EXPECT_NE(a, b);
}

// The stage a progress display reads (Discovery::stage): the generations with their evaluations,
// then validation (every set on every validation seed), then the confirmation a look at a time.
TEST(EvolveService, TheRunStageSaysWhatRunsAndHowFar) {
  for (const int confirmSeeds : {0, 6}) {
    const auto name = "service-stage-" + std::to_string(confirmSeeds);
    const auto config = service::loadConfig(
        tinyEvolveConfig(name, 5),
        {"gp.generations=2", "validation.candidates=3", "validation.seeds=4",
         "validation.confirm_seeds=" + std::to_string(confirmSeeds), "validation.confirm_looks=1"});
    const auto discovery = run::Discovery::start(
        config, {freshDir(name), 1, kVersion, "", {}, 1, {}, "", {}, 0.0, "", "", "", 0.0});
    std::vector<run::RunStage> seen;
    std::vector<long> evaluated;
    const std::atomic<bool> stop{false};
    discovery->run(
        [&](const run::GenerationRecord&) {
          seen.push_back(discovery->stage());
          evaluated.push_back(discovery->progress());
        },
        stop);
    ASSERT_TRUE(discovery->finished());
    ASSERT_EQ(seen.size(), 2U);
    for (std::size_t g = 0; g < seen.size(); ++g) {
      EXPECT_EQ(seen[g].kind, run::RunStage::Generations);
      EXPECT_EQ(seen[g].total, 12);  // The population.
      EXPECT_EQ(seen[g].done, evaluated[g]);
      EXPECT_GT(seen[g].done, 0);
    }
    const auto end = discovery->stage();
    const auto& validation = discovery->validation();
    if (confirmSeeds == 0) {
      EXPECT_EQ(end.kind, run::RunStage::Validation);
      // The original variables, the hall of fame and the no-learning reference, each on the 4
      // validation seeds.
      EXPECT_EQ(end.total, static_cast<int>(validation.sets.size() + 1) * 4);
      EXPECT_EQ(end.done, end.total);
      EXPECT_STREQ(run::stageName(end.kind), "validation");
    } else {
      EXPECT_EQ(end.kind, run::RunStage::Confirmation);
      // The original variables, the winner unless it is them, and no learning.
      const int sets = validation.confirmation.key.empty() ? 2 : 3;
      EXPECT_EQ(end.total, sets * 6);
      EXPECT_EQ(end.done, end.total);  // One look: every seed.
      EXPECT_EQ(static_cast<int>(validation.confirmation.original.size()), 6);
      EXPECT_STREQ(run::stageName(end.kind), "confirmation");
    }
  }
}

// An evaluator whose batches fail from the `failing`-th on (counting from 0): an environment
// that raises, or a worker that dies.
class FailingEvaluator final : public gp::Evaluator {
 public:
  explicit FailingEvaluator(int failing) : left_(failing) {}
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>&) override {
    if (left_-- <= 0) throw std::runtime_error("the environment raised");
    return std::vector<double>(genomes.size(), 1.0);
  }

 private:
  int left_;
};

// A fresh run that fails before its first generation ends leaves no directory; one that fails
// later keeps its checkpoint, to be resumed.
TEST(EvolveService, ARunThatFailsInItsFirstGenerationLeavesNoDirectory) {
  for (const int failing : {0, 1}) {
    const auto dir = freshDir("service-fails-" + std::to_string(failing));
    auto request = tinyRequest("service-fails", dir);
    request.makeEvaluator = [failing](const run::EvaluatorSetup&) {
      return std::make_unique<FailingEvaluator>(failing);
    };
    service::EvolveProgress quiet;
    const std::atomic<bool> stop{false};
    EXPECT_THROW(service::evolve(request, quiet, stop), std::runtime_error);
    EXPECT_EQ(std::filesystem::exists(dir), failing > 0) << failing;
    EXPECT_EQ(std::filesystem::exists(dir + "/checkpoint.json"), failing > 0) << failing;
  }
}

// What a validated run returned opens its line: "confirmed" only where the confirmation found the
// winner better than the original variables.
TEST(EvolveText, AWinnerTheConfirmationFoundNoBetterIsNotConfirmed) {
  run::RunOutcome outcome;
  outcome.validated = true;
  outcome.confirmed = true;
  outcome.winner = {20, 21.0, 2.0, 0.0};
  outcome.original = {20, 20.0, 2.0, 0.0};
  const auto line = [&](double difference, double p) {
    outcome.vsOriginal = {20, difference, 0.5, p};
    std::string text;
    service::EvolveText progress({[&](const std::string& s) { text += s; }, [](auto&) {}});
    progress.runFinished(outcome, "dir", "");
    return text;
  };
  EXPECT_EQ(line(1.0, 0.001).rfind("confirmed: 21 +- ", 0), 0u) << line(1.0, 0.001);
  EXPECT_EQ(line(1.0, 0.3).rfind("not confirmed: 21 +- ", 0), 0u) << line(1.0, 0.3);
  EXPECT_NE(line(1.0, 0.3).find("not significantly different from the original variables"),
            std::string::npos);
  EXPECT_EQ(line(-1.0, 0.001).rfind("not confirmed: ", 0), 0u) << line(-1.0, 0.001);
  outcome.confirmed = false;
  EXPECT_EQ(line(1.0, 0.3).rfind("selection: ", 0), 0u) << line(1.0, 0.3);
}

TEST(EvolveText, DurationsRoundToTheUnitShown) {
  EXPECT_EQ(service::formatDuration(45.2), "45s");
  EXPECT_EQ(service::formatDuration(89.6), "1m30s");
  EXPECT_EQ(service::formatDuration(299.6), "5m00s");  // Not 4m60s.
  EXPECT_EQ(service::formatDuration(3599.7), "60m00s");
  EXPECT_EQ(service::formatDuration(7199.0), "2h00m");
  EXPECT_EQ(service::formatDuration(5460.0), "1h31m");
}

}  // namespace
}  // namespace gpfd::testing
