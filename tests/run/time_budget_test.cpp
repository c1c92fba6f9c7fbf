// A run sized to a time budget (run/time_budget.hpp): the sizes it chose are written into the
// resolved config (and run.json), a resume continues with them, and the resolved config run
// again gives the same run. No assertion here depends on how fast the machine is.
#include "gpfd/run/time_budget.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli_helpers.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/util/error.hpp"
#include "slow_trial_runner.hpp"

namespace gpfd::testing {
namespace {

// Stops the run after its first generation (once its checkpoint is written).
class StopAfterFirst final : public service::EvolveProgress {
 public:
  explicit StopAfterFirst(std::atomic<bool>& stop) : stop_(&stop) {}
  void generationDone(const run::Discovery&, const run::GenerationRecord&,
                      const std::string&) override {
    stop_->store(true);
  }
  void preparedRun(const std::string& text) override { said += text; }
  std::string said;

 private:
  std::atomic<bool>* stop_;
};

// A tiny cart-pole config with a budget of 4 s.
std::string budgetConfig() {
  return writeText("budget.toml", R"(name = "budget"
seed = 5
time_budget = "4s"
[env]
name = "cartpole"
params = { max_steps = 200 }
[learner]
name = "pg"
params = { updates = 4, episodes = 5 }
[fitness]
trials = 2
[genome]
max_features = 4
max_depth = 4
max_size = 15
[validation]
candidates = 3
seeds = 6
confirm_seeds = 6
)");
}

std::string fingerprint(const std::string& dir) {
  return withoutSeconds(readText(dir + "/generations.csv")) + readText(dir + "/validation.csv") +
         readText(dir + "/confirmation.csv") + readText(dir + "/best.features");
}

TEST(TimeBudget, ARunWritesItsSizesAndAResumeReusesThem) {
  const auto dir = freshDir("budget-run");
  service::EvolveRequest request;
  request.config = budgetConfig();
  request.out = {dir, false, "--out"};
  request.threads = 2;
  std::atomic<bool> stop{false};
  StopAfterFirst progress(stop);
  ASSERT_FALSE(service::evolve(request, progress, stop).finished);  // Stopped after generation 0.

  // The sizes chosen are in config.toml, with no budget left to measure again; run.json says what
  // was measured and chosen; the text said it.
  const auto written = run::loadExperimentConfig(dir + "/config.toml");
  EXPECT_EQ(written.timeBudget, 0.0);
  EXPECT_EQ(readText(dir + "/config.toml").find("time_budget"), std::string::npos);
  const auto runJson = nlohmann::json::parse(readText(dir + "/run.json"));
  const auto& chosen = runJson.at("time_budget").at("chosen");
  EXPECT_EQ(runJson.at("time_budget").at("seconds").get<double>(), 4.0);
  EXPECT_EQ(chosen.at("population").get<int>(), written.gp.population);
  EXPECT_GE(chosen.at("generations").get<int>(), 2);
  EXPECT_GE(written.gp.generations, 1);  // Fitted to the budget after generation 0.
  EXPECT_EQ(chosen.at("seeds").get<int>(), written.validation.seeds);
  EXPECT_GE(written.gp.population, run::kMinPopulation);
  EXPECT_GE(written.gp.generations, 2);
  EXPECT_NE(progress.said.find(fmt::format("population {}, generations {}", written.gp.population,
                                           chosen.at("generations").get<int>())),
            std::string::npos)
      << progress.said;

  // The resume continues with the written sizes (also when checked against the budget config)
  // and gives what the resolved config gives when run again from scratch.
  service::EvolveRequest resume;
  resume.resume = dir;
  resume.config = request.config;  // Its time_budget stands for the written sizes.
  service::EvolveProgress quiet;
  const std::atomic<bool> go{false};
  ASSERT_TRUE(service::evolve(resume, quiet, go).finished);
  EXPECT_EQ(readText(dir + "/config.toml").find("time_budget"), std::string::npos);
  const auto again = freshDir("budget-again");
  service::EvolveRequest rerun;
  rerun.config = dir + "/config.toml";
  rerun.out = {again, false, "--out"};
  rerun.threads = 1;
  ASSERT_TRUE(service::evolve(rerun, quiet, go).finished);
  EXPECT_EQ(fingerprint(again), fingerprint(dir));
  EXPECT_FALSE(nlohmann::json::parse(readText(again + "/run.json")).contains("time_budget"));
}

TEST(TimeBudget, SizesGivenReplaceTheConfigsBudget) {
  // The config's 4 s budget yields to gp.population and gp.generations set, and to the
  // generations asked for (--generations, generations=).
  service::EvolveProgress quiet;
  const std::atomic<bool> go{false};
  const auto sized = [&](const std::string& name, std::vector<std::string> overrides,
                         std::optional<int> generations) {
    service::EvolveRequest request;
    request.config = budgetConfig();
    request.overrides = std::move(overrides);
    request.generations = generations;
    request.out = {freshDir(name), false, "--out"};
    request.threads = 1;
    EXPECT_TRUE(service::evolve(request, quiet, go).finished) << name;
    return nlohmann::json::parse(readText(*request.out.dir + "/run.json"));
  };
  EXPECT_FALSE(
      sized("sizes-keys", {"gp.population=6", "gp.generations=1"}, {}).contains("time_budget"));
  EXPECT_FALSE(sized("sizes-flag", {"gp.population=6"}, 1).contains("time_budget"));
}

// The InputError gpfd evolve refuses `request` with ("" where it was accepted).
InputError refusalOf(const service::EvolveRequest& request) {
  service::EvolveProgress quiet;
  const std::atomic<bool> stop{false};
  try {
    service::evolve(request, quiet, stop);
  } catch (const InputError& e) {
    return e;
  }
  return InputError("", "");
}

// The InputError gpfd evolve gives cartpole-quick with `budget` for `runs` runs ("" if none).
InputError budgetRefusal(const std::string& budget, int runs, const std::string& dir) {
  service::EvolveRequest request;
  request.config = "cartpole-quick";
  request.overrides = {"time_budget=" + budget};
  if (runs > 1) request.runs = runs;
  request.out = {freshDir(dir), false, "--out"};
  return refusalOf(request);
}

TEST(TimeBudget, ABudgetTooShortForTheSmallestRunIsRefused) {
  const auto e = budgetRefusal("0.05", 1, "budget-short");
  const std::string what = e.what();
  ASSERT_FALSE(what.empty()) << "a 0.05 s budget was accepted";
  EXPECT_EQ(e.where(), "time_budget (--time-budget)");
  // Refused before measuring (one training predicts it) or after, naming the smallest run.
  EXPECT_NE(what.find("is too short here: "), std::string::npos) << what;
  EXPECT_NE(what.find("the smallest run"), std::string::npos) << what;
  EXPECT_NE(what.find("give at least"), std::string::npos) << what;
}

// cartpole-quick with `budget` and a choice of two alternatives, trained on `runner`.
service::EvolveRequest choosingRequest(const std::string& budget, const std::string& dir,
                                       std::shared_ptr<SlowTrialRunner> runner) {
  service::EvolveRequest request;
  request.config = "cartpole-quick";
  request.overrides = {"time_budget=" + budget, R"(learner.choose={ rprop = ["small", "large"] })"};
  request.out = {freshDir(dir), false, "--out"};
  request.trialRunner = std::move(runner);
  return request;
}

// The trainings a cartpole-quick call with a learner choice and `budget` played before it was
// refused, each a second long (SlowTrialRunner); a failure where it was accepted, or went on past
// 10 trainings.
int trainingsBeforeTheRefusal(const std::string& budget, const std::string& dir) {
  auto runner = std::make_shared<SlowTrialRunner>(0, 10);
  try {
    const std::string what = refusalOf(choosingRequest(budget, dir, runner)).what();
    if (what.empty()) {
      ADD_FAILURE() << "a " << budget << " s budget was accepted with trainings of a second";
    } else {
      EXPECT_NE(what.find("is too short here: "), std::string::npos) << what;
      EXPECT_NE(what.find("give at least"), std::string::npos) << what;
    }
  } catch (const SlowTrialRunner::TooManyTrainings&) {
    ADD_FAILURE() << "a " << budget << " s budget went on past 10 trainings of a second";
  }
  return runner->calls;
}

// A learner choice that took the whole budget is refused at once, predicted from its training,
// without timing one more.
TEST(TimeBudget, AChoiceThatTookTheWholeBudgetIsRefusedWithoutTrainingMore) {
  EXPECT_EQ(trainingsBeforeTheRefusal("0.5", "budget-choice-took-all"), 1);
}

// One training longer than the choice's share of a budget that the choice leaves mostly unspent
// (Swimmer-v5 stepped in Python: 171-207 s a training, of 180): refused from the choice's
// one-update training, before any whole training (cartpole-quick's confirmation: 50 updates, so
// about 25 s predicted of a 10-s share).
TEST(TimeBudget, AFirstTrainingPredictedPastTheChoicesShareIsRefusedBeforeItIsPlayed) {
  EXPECT_EQ(trainingsBeforeTheRefusal("40", "budget-choice-predicted"), 1);
}

// A first training predicted within the choice's share (25.5 s of 30), of a call that cannot fit
// anyway (measuring alone about 490 s): refused from the one-update training, before the choice
// plays a whole one (Swimmer-v5 in Python: one of 4 calls with the default budget played its
// first training, and was refused after 95.5 s of 180).
TEST(TimeBudget, ACallTheFirstTrainingsPredictionCannotFitIsRefusedBeforeItIsPlayed) {
  EXPECT_EQ(trainingsBeforeTheRefusal("120", "budget-choice-predicted-call"), 1);
}

// Under MPI a budget is refused before anything is timed, the learner's choice included.
TEST(TimeBudget, ABudgetUnderMpiIsRefusedBeforeTheChoiceTrains) {
  auto runner = std::make_shared<SlowTrialRunner>(0, 1);
  auto request = choosingRequest("600", "budget-mpi", runner);
  request.processes = 2;
  const auto e = refusalOf(request);
  const std::string what = e.what();
  ASSERT_FALSE(what.empty()) << "a budget under MPI was accepted";
  EXPECT_NE(what.find("not measured under MPI"), std::string::npos) << what;
  EXPECT_NE(e.where().find("time_budget"), std::string::npos) << e.where();
  EXPECT_EQ(runner->calls, 0);
}

TEST(TimeBudget, ABudgetTooShortForItsRunsNamesTheWholeBudget) {
  const std::string what = budgetRefusal("0.5", 4, "budget-short-runs").what();
  ASSERT_FALSE(what.empty()) << "a 0.5 s budget for 4 runs was accepted";
  EXPECT_NE(what.find("for 4 runs is too short here"), std::string::npos) << what;
  EXPECT_NE(what.find("fewer runs"), std::string::npos) << what;
}

TEST(TimeBudget, TheKeyReadsSecondsOrTextAndBadValuesNameIt) {
  const auto path = tinyEvolveConfig("budget-key", 1);  // Without a budget.
  EXPECT_EQ(service::loadConfig(path, {"time_budget=\"1h30m\""}).timeBudget, 5400.0);
  EXPECT_EQ(service::loadConfig(path, {"time_budget=90"}).timeBudget, 90.0);
  EXPECT_EQ(service::loadConfig(path, {}).timeBudget, 0.0);
  const auto withBudget = service::loadConfig(path, {"time_budget=\"10m\""});
  EXPECT_NE(run::formatExperimentConfig(withBudget).find("time_budget = 600"), std::string::npos);
  for (const char* bad : {"time_budget=\"ten minutes\"", "time_budget=0", "time_budget=-3"}) {
    try {
      service::loadConfig(path, {bad});
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(e.where().find("time_budget"), std::string::npos) << bad << ": " << e.where();
    }
  }
}

TEST(TimeBudget, TheFlagsBadValuesAreErrorsNamingIt) {
  const auto bad = runGpfd("evolve --time-budget 10x --quiet --out " + freshDir("budget-flag"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("not '10x' (--time-budget)"), std::string::npos) << bad.output;
  const auto both =
      runGpfd("evolve --time-budget 1m --population 20 --quiet --out " + freshDir("budget-both"));
  EXPECT_EQ(both.status, 2) << both.output;
  EXPECT_NE(both.output.find("give either it or them (--time-budget)"), std::string::npos)
      << both.output;
}

}  // namespace
}  // namespace gpfd::testing
