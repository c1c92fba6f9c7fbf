// The learner's settings chosen on the task (learner.choose, run/learner_choice.hpp): the choice
// is the best of the candidates for the original variables, the same on any number of threads,
// written into the resolved config (and run.json) with no choice left, kept by a resume, and
// replaced by a value given; bad choices are errors naming the key.
#include "gpfd/run/learner_choice.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_helpers.hpp"
#include "gpfd/service/assess.hpp"
#include "gpfd/service/configs.hpp"
#include "gpfd/service/evolve.hpp"
#include "gpfd/util/error.hpp"
#include "slow_trial_runner.hpp"

namespace gpfd::testing {
namespace {

// A tiny cart-pole config choosing Rprop's steps.
std::string choosingConfig() {
  return writeText("choose.toml", R"(name = "choose"
seed = 3
[env]
name = "cartpole"
params = { max_steps = 200 }
[learner]
name = "pg"
params = { updates = 4, episodes = 5, rprop = "large" }
choose = { rprop = ["small", "large"] }
choose_seeds = 4
[fitness]
trials = 2
[gp]
population = 6
generations = 2
[validation]
candidates = 3
seeds = 6
confirm_seeds = 6
confirm_params = { updates = 8 }
)");
}

class Said final : public service::EvolveProgress {
 public:
  void preparing(const std::string& text) override { said += text; }
  void preparedRun(const std::string& text) override { said += text; }
  std::string said;
};

// Resumes the run in `dir` to 3 generations, checked against `config`: whether it finished.
bool resumeFinishes(const std::string& dir, const std::string& config) {
  service::EvolveRequest resume;
  resume.resume = dir;
  resume.config = config;
  resume.generations = 3;
  service::EvolveProgress quiet;
  const std::atomic<bool> go{false};
  return service::evolve(resume, quiet, go).finished;
}

// A run of choosingConfig() written to `file` with `choose` (TOML lines) in place of its
// learner.choose, on 2 threads into `dir`: a resume reads the config as it is in the file.
service::EvolveRequest choosingRun(const std::string& file, const std::string& choose,
                                   const std::string& dir) {
  auto text = readText(choosingConfig());
  const std::string listed = "choose = { rprop = [\"small\", \"large\"] }";
  text.replace(text.find(listed), listed.size(), choose);
  service::EvolveRequest request;
  request.config = writeText(file, text);
  request.out = {dir, false, "--out"};
  request.threads = 2;
  return request;
}

TEST(LearnerChoice, CandidatesAreEveryCombinationInOrder) {
  auto config = service::loadConfig(choosingConfig(), {"learner.choose.episodes=[3, 5]"});
  const auto candidates = run::learnerCandidates(config);
  ASSERT_EQ(candidates.size(), 4u);
  EXPECT_EQ(candidates[0],
            (std::map<std::string, std::string>{{"episodes", "3"}, {"rprop", "small"}}));
  EXPECT_EQ(candidates[1],
            (std::map<std::string, std::string>{{"episodes", "3"}, {"rprop", "large"}}));
  EXPECT_EQ(candidates[3],
            (std::map<std::string, std::string>{{"episodes", "5"}, {"rprop", "large"}}));
}

TEST(LearnerChoice, PicksTheBestMeanTheSameOnAnyThreads) {
  const auto config = service::loadConfig(choosingConfig(), {});
  run::ThreadTrialRunner one(1), two(2);
  const auto a = run::chooseLearnerSettings(config, one);
  const auto b = run::chooseLearnerSettings(config, two);
  ASSERT_EQ(a.means.size(), 2u);
  EXPECT_EQ(a.means, b.means);  // Bit for bit.
  EXPECT_EQ(a.chosen, b.chosen);
  EXPECT_NE(a.means[0], a.means[1]);  // The step sizes change what the learner does.
  EXPECT_EQ(a.chosen, static_cast<std::size_t>(std::max_element(a.means.begin(), a.means.end()) -
                                               a.means.begin()));
  const auto chosen = run::withLearnerChoice(config, a);
  EXPECT_TRUE(chosen.learnerChoices.empty());
  EXPECT_EQ(chosen.learnerParams.at("rprop"), a.candidates[a.chosen].at("rprop"));
  EXPECT_EQ(run::formatExperimentConfig(chosen).find("choose_seeds"), std::string::npos);
  // Another seed draws other training seeds.
  auto reseeded = config;
  reseeded.seed = 4;
  EXPECT_NE(run::chooseLearnerSettings(reseeded, one).means, a.means);
}

TEST(LearnerChoice, AConfigWithAChoiceReadsBackAsWritten) {
  const auto config = service::loadConfig(choosingConfig(), {});
  const auto text = run::formatExperimentConfig(config);
  EXPECT_NE(text.find("choose_seeds = 4"), std::string::npos) << text;
  const auto again = run::parseExperimentConfig(text, "written");
  EXPECT_EQ(again.learnerChoices, config.learnerChoices);
  EXPECT_EQ(again.choiceSeeds, 4);
}

TEST(LearnerChoice, ARunWritesTheChoiceAndAResumeKeepsIt) {
  const auto dir = freshDir("choose-run");
  service::EvolveRequest request;
  request.config = choosingConfig();
  request.out = {dir, false, "--out"};
  request.threads = 2;
  Said progress;
  const std::atomic<bool> go{false};
  ASSERT_TRUE(service::evolve(request, progress, go).finished);
  const auto config = service::loadConfig(request.config, {});
  run::ThreadTrialRunner threads(1);
  const auto expected = run::chooseLearnerSettings(config, threads);
  const auto rprop = expected.candidates[expected.chosen].at("rprop");
  const auto written = run::loadExperimentConfig(dir + "/config.toml");
  EXPECT_TRUE(written.learnerChoices.empty());
  EXPECT_EQ(written.learnerParams.at("rprop"), rprop);
  const auto runJson = nlohmann::json::parse(readText(dir + "/run.json"));
  EXPECT_EQ(runJson.at("learner_choice").at("chosen").at("rprop").get<std::string>(), rprop);
  EXPECT_EQ(runJson.at("learner_choice").at("tried").size(), 2u);
  EXPECT_NE(progress.said.find("learner settings chosen on this task: rprop = " + rprop),
            std::string::npos)
      << progress.said;

  // A resume checked against the choosing config is accepted (it stands for the choice made).
  EXPECT_TRUE(resumeFinishes(dir, request.config));
  EXPECT_EQ(run::loadExperimentConfig(dir + "/config.toml").learnerParams.at("rprop"), rprop);
}

TEST(LearnerChoice, AValueGivenReplacesTheChoice) {
  // Wherever a config is read (gpfd evolve, gpfd assess, Python), with its overrides.
  EXPECT_TRUE(service::loadConfig(choosingConfig(), {"learner.params.rprop=\"small\""})
                  .learnerChoices.empty());
  EXPECT_EQ(
      service::loadConfig(choosingConfig(), {"learner.params.episodes=3"}).learnerChoices.size(),
      1u);
  service::EvolveRequest request;
  request.config = choosingConfig();
  request.overrides = {"learner.params.rprop=\"small\""};
  request.out = {freshDir("choose-given"), false, "--out"};
  request.threads = 1;
  Said progress;
  const std::atomic<bool> go{false};
  ASSERT_TRUE(service::evolve(request, progress, go).finished);
  EXPECT_EQ(progress.said.find("learner settings chosen"), std::string::npos) << progress.said;
  const auto runJson = nlohmann::json::parse(readText(*request.out.dir + "/run.json"));
  EXPECT_FALSE(runJson.contains("learner_choice"));
  EXPECT_EQ(run::loadExperimentConfig(*request.out.dir + "/config.toml").learnerParams.at("rprop"),
            "small");
}

// gpfd assess on choosingConfig(): the original variables, 2 runs, nothing written.
service::AssessRequest rawAssessment() {
  service::AssessRequest request;
  request.config = choosingConfig();
  request.raw = true;
  request.runs = 2;
  request.seed = 3;
  request.threads = 1;
  request.write = false;
  return request;
}

TEST(LearnerChoice, AssessChoosesAsEvolveDoes) {
  const auto request = rawAssessment();
  std::string printed;
  const auto result = service::assess(request, [&](const std::string& t) { printed += t; });
  const auto config = service::loadConfig(request.config, {});
  run::ThreadTrialRunner threads(2);
  const auto expected = run::chooseLearnerSettings(config, threads);
  EXPECT_TRUE(result.config.learnerChoices.empty());
  EXPECT_EQ(result.config.learnerParams.at("rprop"),
            expected.candidates[expected.chosen].at("rprop"));
  EXPECT_NE(printed.find("learner settings chosen on this task"), std::string::npos) << printed;
}

// The error (where: what) that validating choosingConfig() with `overrides` raises; "" if none.
std::string refusal(const std::vector<std::string>& overrides) {
  try {
    run::validate(service::loadConfig(choosingConfig(), overrides));
  } catch (const InputError& e) {
    return std::string(e.where()) + ": " + e.what();
  }
  return std::string();
}

TEST(LearnerChoice, BadChoicesAreErrorsNamingTheKey) {
  const auto refused = [](const std::string& override) { return refusal({override}); };
  const auto unknown = refused("learner.choose.rpop=[\"small\"]");
  EXPECT_NE(unknown.find("learner.choose.rpop"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("did you mean 'rprop'"), std::string::npos) << unknown;
  const auto value = refused("learner.choose.rprop=[\"large\", \"tiny\"]");
  EXPECT_NE(value.find("learner.choose.rprop"), std::string::npos) << value;
  EXPECT_NE(value.find("tiny"), std::string::npos) << value;
  const auto empty = refused("learner.choose.rprop=[]");
  EXPECT_NE(empty.find("must list at least one value"), std::string::npos) << empty;
  const auto seeds = refused("learner.choose_seeds=1");
  EXPECT_NE(seeds.find("learner.choose_seeds"), std::string::npos) << seeds;
  const auto many = refused(
      "learner.choose={ rprop = [\"large\", \"small\"], episodes = [1, 2, 3], updates = [1, 2, 3] "
      "}");
  EXPECT_NE(many.find("18 combinations"), std::string::npos) << many;
}

// learner.choose_significance: an earlier candidate is kept unless the best beats it clearly.
TEST(LearnerChoice, ASignificanceKeepsAnEarlierCandidateUnlessTheBestIsClearlyBetter) {
  run::ThreadTrialRunner threads(2);
  auto config = service::loadConfig(choosingConfig(), {});
  const auto plain = run::chooseLearnerSettings(config, threads);
  ASSERT_EQ(plain.chosen, 1u) << "the test needs the second listed to have the best mean";
  config.choiceSignificance = 1e-9;  // 4 seeds cannot show a difference this clearly.
  const auto strict = run::chooseLearnerSettings(config, threads);
  EXPECT_EQ(strict.means, plain.means);
  EXPECT_EQ(strict.chosen, 0u);
  // Natural steps of a KL of 1e-12 learn nothing: steps that learn beat them clearly.
  auto frozen = service::loadConfig(
      choosingConfig(), {"learner.choose=[{ step = \"natural\", kl = 1e-12 }, { rprop = "
                         "\"large\" }]",
                         "learner.choose_significance=0.05", "learner.choose_seeds=8",
                         "validation.confirm_params={ updates = 20 }"});
  const auto learns = run::chooseLearnerSettings(frozen, threads);
  ASSERT_LT(learns.means[0], learns.means[1]);
  EXPECT_EQ(learns.chosen, 1u) << learns.means[0] << " " << learns.means[1];
  EXPECT_NE(run::formatExperimentConfig(frozen).find("choose_significance = 0.05"),
            std::string::npos);
}

// A runner that trains nothing: each curve's one row is a score set by the task's settings
// (learner.params.rprop): the original variables' score, or for set s of random genomes a
// spread of s times a step.
class ScriptedRunner final : public run::TrialRunner {
 public:
  struct Scores {
    double original, randomStep;
  };
  std::map<std::string, Scores> byRprop;
  std::vector<std::vector<rl::LearningCurve>> run(
      const run::LearningTask& task, const run::TrialBatch& batch,
      const std::function<void(std::size_t)>&) override {
    const Scores scores = byRprop.at(task.config().learnerParams.at("rprop"));
    std::vector<std::vector<rl::LearningCurve>> curves(batch.sets.size());
    for (std::size_t s = 0; s < batch.sets.size(); ++s) {
      const bool random = batch.sets[s].kind == run::TrialFeatures::Kind::Genome;
      rl::LearningCurve curve;
      curve.points.emplace_back();
      curve.points.back().meanReturn =
          random ? static_cast<double>(s) * scores.randomStep : scores.original;
      curves[s].assign(batch.runs(), curve);
    }
    return curves;
  }
};

// learner.choose_random_sets: the learner that makes the most of GP's random sets wins where
// they beat the original variables, though it trains the original variables worse.
TEST(LearnerChoice, RandomSetsScoreWhatTheLearnerMakesOfGPsFirstFeatures) {
  ScriptedRunner runner;
  // 8 random sets: the best quarter is sets 6 and 7, 6.5 steps on average.
  runner.byRprop = {{"small", {10.0, 4.0}}, {"large", {12.0, 1.0}}};
  const std::vector<std::string> scoredByFinal = {"validation.confirm_measure=\"final\""};
  auto config = service::loadConfig(choosingConfig(), scoredByFinal);
  const auto plain = run::chooseLearnerSettings(config, runner);
  EXPECT_EQ(plain.candidates[plain.chosen].at("rprop"), "large");
  EXPECT_TRUE(plain.randomSetsBest.empty());
  EXPECT_EQ(run::learnerChoiceJson(plain).find("random_sets_best"), std::string::npos);
  auto overrides = scoredByFinal;
  overrides.push_back("learner.choose_random_sets=8");
  config = service::loadConfig(choosingConfig(), overrides);
  const auto random = run::chooseLearnerSettings(config, runner);
  EXPECT_EQ(random.candidates[random.chosen].at("rprop"), "small");
  EXPECT_EQ(random.means, plain.means);
  EXPECT_EQ(random.randomSetsBest, (std::vector<double>{26.0, 6.5}));
  EXPECT_EQ(random.merits, (std::vector<double>{26.0, 12.0}));  // The better of the two.
  EXPECT_NE(run::learnerChoiceText(random).find("best quarter of 8 random feature sets"),
            std::string::npos);
  EXPECT_NE(run::learnerChoiceJson(random).find("\"random_sets_best\":26.0"), std::string::npos)
      << run::learnerChoiceJson(random);
  const auto again = run::parseExperimentConfig(run::formatExperimentConfig(config), "written");
  EXPECT_EQ(again.choiceRandomSets, 8);
  const auto both = refusal({"learner.choose_random_sets=8", "learner.choose_significance=0.05"});
  EXPECT_NE(both.find("learner.choose_random_sets"), std::string::npos) << both;
}

// The random sets are drawn from the choice's stream: the same on any number of threads, and
// trained on real learners they change nothing of the original variables' scores.
TEST(LearnerChoice, RandomSetsAreTheSameOnAnyThreads) {
  const auto config = service::loadConfig(choosingConfig(), {"learner.choose_random_sets=4"});
  run::ThreadTrialRunner one(1), two(2);
  const auto a = run::chooseLearnerSettings(config, one);
  const auto b = run::chooseLearnerSettings(config, two);
  EXPECT_EQ(a.randomSetsBest, b.randomSetsBest);  // Bit for bit.
  EXPECT_EQ(a.chosen, b.chosen);
  EXPECT_EQ(a.means,
            run::chooseLearnerSettings(service::loadConfig(choosingConfig(), {}), one).means);
}

// learner.choose as alternatives: each a set of parameters over learner.params.
const char* kAlternatives =
    "learner.choose=[{ step = \"natural\", updates = 6, learn_std = true }, { rprop = \"small\" "
    "}]";

TEST(LearnerChoice, AlternativesAreTheCandidatesAsListedAndReadBackAsWritten) {
  const auto config = service::loadConfig(choosingConfig(), {kAlternatives});
  EXPECT_TRUE(config.learnerChoices.empty());
  ASSERT_TRUE(run::choosesLearner(config));
  const auto candidates = run::learnerCandidates(config);
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0], (std::map<std::string, std::string>{
                               {"learn_std", "true"}, {"step", "natural"}, {"updates", "6"}}));
  EXPECT_EQ(candidates[1], (std::map<std::string, std::string>{{"rprop", "small"}}));
  const auto again = run::parseExperimentConfig(run::formatExperimentConfig(config), "written");
  EXPECT_EQ(again.learnerAlternatives, config.learnerAlternatives);
  EXPECT_EQ(again.choiceSeeds, 4);
}

// The choice on one thread, checked to be the same on two (bit for bit).
run::LearnerChoice choiceOnAnyThreads(const run::ExperimentConfig& config) {
  run::ThreadTrialRunner one(1), two(2);
  auto choice = run::chooseLearnerSettings(config, one);
  EXPECT_EQ(choice.means, run::chooseLearnerSettings(config, two).means);
  return choice;
}

TEST(LearnerChoice, AnAlternativeChosenSetsAllItsParameters) {
  const auto config = service::loadConfig(choosingConfig(), {kAlternatives});
  const auto a = choiceOnAnyThreads(config);
  ASSERT_EQ(a.means.size(), 2u);
  EXPECT_NE(a.means[0], a.means[1]);
  const auto chosen = run::withLearnerChoice(config, a);
  EXPECT_FALSE(run::choosesLearner(chosen));
  for (const auto& [key, value] : a.candidates[a.chosen]) {
    EXPECT_EQ(chosen.learnerParams.at(key), value) << key;
  }
  EXPECT_EQ(chosen.learnerParams.at("episodes"), "5");  // learner.params' own stay.
}

// A value given drops the alternatives that set it otherwise (those that do not set it stay); a
// single one left is applied.
TEST(LearnerChoice, AValueGivenDropsTheAlternativesItContradicts) {
  const auto three =
      std::string(kAlternatives)
          .replace(std::string(kAlternatives).rfind(']'), 1, ", { rprop = \"large\" }]");
  const auto large = service::loadConfig(choosingConfig(), {three, "learner.params.rprop=large"});
  ASSERT_EQ(large.learnerAlternatives.size(), 2u);
  EXPECT_EQ(large.learnerAlternatives[0].at("step"), "natural");
  EXPECT_EQ(large.learnerAlternatives[1].at("rprop"), "large");
  const auto rprop =
      service::loadConfig(choosingConfig(), {kAlternatives, "learner.params.step=rprop"});
  EXPECT_FALSE(run::choosesLearner(rprop));
  EXPECT_EQ(rprop.learnerParams.at("rprop"), "small");
  EXPECT_EQ(rprop.learnerParams.at("step"), "rprop");
  EXPECT_EQ(rprop.learnerParams.at("updates"), "4");
  const auto none = service::loadConfig(
      choosingConfig(), {kAlternatives, "learner.params.updates=9", "learner.params.rprop=large"});
  EXPECT_FALSE(run::choosesLearner(none));
}

TEST(LearnerChoice, BadAlternativesAreErrorsNamingTheKey) {
  const auto refused = [](const std::string& override) {
    return refusal({"learner.choose={}", override});
  };
  const auto unknown = refused("learner.choose=[{ rprop = \"small\" }, { stepp = \"natural\" }]");
  EXPECT_NE(unknown.find("learner.choose[1].stepp"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("did you mean 'step'"), std::string::npos) << unknown;
  const auto value = refused("learner.choose=[{ step = \"natral\" }]");
  EXPECT_NE(value.find("natral"), std::string::npos) << value;
  EXPECT_NE(value.find("learner.choose[0].step"), std::string::npos) << value;
  const auto empty = refused("learner.choose=[]");
  EXPECT_NE(empty.find("at least one alternative"), std::string::npos) << empty;
  const auto notTables = refused("learner.choose=[1, 2]");
  EXPECT_NE(notTables.find("array of tables"), std::string::npos) << notTables;
}

// gpfd assess's --param, like gpfd evolve's override, wins over the choice; its --budget does not
// count as a value given (the assessment's length, never a choice's).
TEST(LearnerChoice, AnAssessmentsParamsWinOverTheChoice) {
  auto request = rawAssessment();
  request.budget = 2;
  request.params = {"rprop=small"};
  std::string printed;
  auto result = service::assess(request, [&](const std::string& t) { printed += t; });
  EXPECT_FALSE(run::choosesLearner(result.config));
  EXPECT_EQ(printed.find("learner settings chosen"), std::string::npos) << printed;
  // Alternatives: the one the given step leaves is applied whole, the budget aside.
  request.overrides = {kAlternatives};
  request.params = {"step=rprop"};
  printed.clear();
  result = service::assess(request, [&](const std::string& t) { printed += t; });
  EXPECT_EQ(printed.find("learner settings chosen"), std::string::npos) << printed;
  EXPECT_EQ(result.config.learnerParams.at("rprop"), "small");
  EXPECT_EQ(result.config.assessParams.at("updates"), "2");
}

}  // namespace
}  // namespace gpfd::testing

namespace gpfd::testing {
namespace {

// The no-learning reference trained beside the original variables (on the same seeds), and a
// time allowance that cuts the choice to its first candidate, said and recorded.
TEST(LearnerChoice, TrainsNoLearningBesideAndFitsAnAllowance) {
  const auto config = service::loadConfig(choosingConfig(), {});
  run::ThreadTrialRunner threads(2);
  const auto whole = run::chooseLearnerSettings(config, threads);
  ASSERT_EQ(whole.noLearningMeans.size(), 2u);
  EXPECT_FALSE(whole.nothingLearns);  // Cart-pole learns with either step size.
  EXPECT_EQ(whole.cut, run::LearnerChoice::Cut::None);
  EXPECT_GT(whole.firstSeconds, 0.0);
  const auto json = nlohmann::json::parse(run::learnerChoiceJson(whole));
  EXPECT_FALSE(json.contains("cut"));
  EXPECT_EQ(json["tried"][0]["no_learning"].get<double>(), whole.noLearningMeans[0]);
  // Half a second, the first training slowed past it (its one-update timing fast): the first
  // training only, the first candidate kept; its score is that training's in the whole choice
  // (the batches split, the curves the same).
  SlowTrialRunner slowAfterTheUnit(1);
  const auto cut = run::chooseLearnerSettings(config, slowAfterTheUnit, 0.5, 2);
  EXPECT_EQ(slowAfterTheUnit.calls, 2);  // The one-update training and the first.
  EXPECT_EQ(cut.cut, run::LearnerChoice::Cut::All);
  EXPECT_FALSE(cut.firstPredicted);
  ASSERT_EQ(cut.candidates.size(), 1u);
  EXPECT_EQ(cut.chosen, 0u);
  ASSERT_EQ(cut.scores[0].size(), 1u);
  EXPECT_EQ(cut.scores[0][0], whole.scores[0][0]);
  EXPECT_FALSE(cut.nothingLearns);
  EXPECT_NE(run::learnerChoiceText(cut).find("NOT chosen"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(run::learnerChoiceJson(cut))["cut"], "all");
}

// A training of one update, timed first, predicts the first training (8 updates: 4.5 times its
// one-update training): where that alone would pass the allowance, no training of the choice is
// played, and the first candidate is kept untrained, said and recorded.
TEST(LearnerChoice, AFirstTrainingPredictedPastTheAllowanceIsNotPlayed) {
  const auto config = service::loadConfig(choosingConfig(), {});
  SlowTrialRunner slow;  // Each training 1 s more: the first predicted at 4.5 s at least.
  const auto untrained = run::chooseLearnerSettings(config, slow, 3.0, 1);
  EXPECT_EQ(slow.calls, 1);
  EXPECT_TRUE(untrained.firstPredicted);
  EXPECT_EQ(untrained.cut, run::LearnerChoice::Cut::All);
  ASSERT_EQ(untrained.candidates.size(), 1u);
  EXPECT_TRUE(untrained.scores[0].empty());
  EXPECT_GE(untrained.firstSeconds, 4.5);
  EXPECT_FALSE(untrained.nothingLearns);
  EXPECT_NE(run::learnerChoiceText(untrained).find("kept untrained"), std::string::npos);
  const auto json = nlohmann::json::parse(run::learnerChoiceJson(untrained));
  EXPECT_EQ(json["first_seconds_predicted"].get<double>(), untrained.firstSeconds);
  // Without an allowance nothing is timed first: the same trainings as ever.
  SlowTrialRunner counted(1000);
  run::chooseLearnerSettings(config, counted);
  const auto whole = run::chooseLearnerSettings(config, slow, 30.0, 1);
  EXPECT_FALSE(whole.firstPredicted);
  EXPECT_EQ(slow.calls - 1, counted.calls + 1);  // The one-update training more.
}

// The first candidate's whole cost, measured, sizes the others again: where they would pass the
// allowance that the first training said they fit, the first candidate is kept, said.
TEST(LearnerChoice, TheFirstCandidatesCostCutsTheOthersThatWouldPassTheAllowance) {
  const auto config = service::loadConfig(choosingConfig(), {});
  run::ThreadTrialRunner one(1);
  const auto whole = run::chooseLearnerSettings(config, one);
  SlowTrialRunner slow(2);  // The one-update training and the first training fast.
  // 1.5 s: the first training (milliseconds) predicts far less; the first candidate takes 1 s
  // more, so the two about 2 s.
  const auto cut = run::chooseLearnerSettings(config, slow, 1.5, 1);
  EXPECT_EQ(cut.cut, run::LearnerChoice::Cut::Candidates);
  ASSERT_EQ(cut.candidates.size(), 1u);
  EXPECT_EQ(cut.scores[0], whole.scores[0]);  // The first candidate trained whole.
  EXPECT_GT(cut.predictedSeconds, 1.5);
  EXPECT_NE(run::learnerChoiceText(cut).find("NOT chosen"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(run::learnerChoiceJson(cut))["cut"], "candidates");
}

// Where the original variables and no learning score alike with every candidate (a learner of
// no updates learns nothing), the choice says so, and a run stops before GP with what to change.
TEST(LearnerChoice, NothingLearnsStopsTheRun) {
  const auto config = service::loadConfig(
      choosingConfig(), {"learner.params.updates=0", "validation.confirm_params.updates=0"});
  run::ThreadTrialRunner threads(2);
  const auto choice = run::chooseLearnerSettings(config, threads);
  ASSERT_TRUE(choice.nothingLearns);
  EXPECT_EQ(choice.means, choice.noLearningMeans);
  EXPECT_NE(run::nothingLearnsText(choice).find("nothing learns here"), std::string::npos);
  const auto dir = freshDir("choose-nothing");
  service::EvolveRequest request;
  request.config = choosingConfig();
  request.overrides = {"learner.params.updates=0", "validation.confirm_params.updates=0"};
  request.out = {dir, false, "--out"};
  Said progress;
  const std::atomic<bool> go{false};
  try {
    service::evolve(request, progress, go);
    FAIL() << "a run where nothing learns went on";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nothing learns here"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir));  // Stopped before anything was written.
  // A learner that learns is not stopped (the first test's config, which trains).
  EXPECT_FALSE(
      run::chooseLearnerSettings(service::loadConfig(choosingConfig(), {}), threads).nothingLearns);
}

}  // namespace
}  // namespace gpfd::testing

namespace gpfd::testing {
namespace {

// learner.choose naming another learner: pg's natural steps of a KL of 1e-12 (which learn
// nothing) against ARS (Mania, Guy & Recht 2018) with 2 directions, each given as many episodes
// as pg plays: confirmation 9 rows of 5 episodes (45) become 10 ARS iterations + 1 of 4 (44).
const char* kArsAlternative =
    "learner.choose=[{ step = \"natural\", kl = 1e-12 }, { learner = \"ars\", n_delta = 2, "
    "learning_rate = 0.1, greedy_last = true }]";

TEST(LearnerChoice, ACandidateMayNameAnotherLearnerAtEqualEpisodes) {
  const auto config = service::loadConfig(choosingConfig(), {kArsAlternative});
  EXPECT_EQ(run::trainingEpisodes("pg", {{"updates", "8"}, {"episodes", "5"}}), 45);
  EXPECT_EQ(run::trainingEpisodes("ars", {{"updates", "10"}, {"n_delta", "2"}}), 44);
  EXPECT_EQ(run::trainingEpisodes("lpi", {{"iterations", "2"}, {"games", "3"}}), 9);
  EXPECT_EQ(run::trainingEpisodes("ars", {}), 101 * 16);  // Its defaults: 100 x 8 directions.
  const auto ars = run::withCandidate(config, run::learnerCandidates(config)[1]);
  EXPECT_EQ(ars.learner, "ars");
  EXPECT_FALSE(run::choosesLearner(ars));
  // Its own parameters (none of pg's learner.params: rprop, episodes), the budgets matched:
  // trials 5 x 5 = 25 episodes -> 5 iterations + 1 of 4 (24); confirmation 45 -> 10 (44).
  EXPECT_EQ(
      ars.learnerParams,
      (std::map<std::string, std::string>{
          {"greedy_last", "true"}, {"learning_rate", "0.1"}, {"n_delta", "2"}, {"updates", "5"}}));
  EXPECT_EQ(ars.validation.confirmParams, (std::map<std::string, std::string>{{"updates", "10"}}));
  EXPECT_TRUE(ars.validation.params.empty());  // The trials' budget, as in the config.
  run::validate(ars);
  // The config's own learner named is an alternative over learner.params as before.
  const auto same = service::loadConfig(
      choosingConfig(), {"learner.choose=[{ learner = \"pg\", rprop = \"small\" }, {}]"});
  const auto pg = run::withCandidate(same, run::learnerCandidates(same)[0]);
  EXPECT_EQ(pg.learner, "pg");
  EXPECT_EQ(pg.learnerParams.at("rprop"), "small");
  EXPECT_EQ(pg.learnerParams.at("episodes"), "5");
}

TEST(LearnerChoice, ALearnerThatTrainsBetterIsChosenAndNamed) {
  const auto config = service::loadConfig(choosingConfig(), {kArsAlternative});
  const auto a = choiceOnAnyThreads(config);
  run::ThreadTrialRunner one(1);
  ASSERT_EQ(a.means.size(), 2u);
  EXPECT_EQ(a.learners, (std::vector<std::string>{"pg", "ars"}));
  EXPECT_EQ(a.episodes, (std::vector<std::int64_t>{45, 44}));
  ASSERT_GT(a.means[1], a.means[0]) << "ARS must train cart-pole better than a frozen pg here";
  EXPECT_EQ(a.chosen, 1u);
  const auto chosen = run::withLearnerChoice(config, a);
  EXPECT_EQ(chosen.learner, "ars");
  EXPECT_EQ(chosen.learnerParams.at("updates"), "5");
  const auto json = nlohmann::json::parse(run::learnerChoiceJson(a));
  EXPECT_EQ(json.at("learner"), "ars");
  EXPECT_EQ(json.at("chosen").at("learner"), "ars");
  EXPECT_EQ(json.at("tried")[0].at("learner"), "pg");
  EXPECT_EQ(json.at("tried")[1].at("episodes"), 44);
  const auto text = run::learnerChoiceText(a);
  EXPECT_NE(text.find("chosen on this task: ars with"), std::string::npos) << text;
  EXPECT_NE(text.find("(45 episodes a training)"), std::string::npos) << text;
  // The same learner's candidates keep their JSON (no learner, no episodes).
  const auto plain = nlohmann::json::parse(run::learnerChoiceJson(
      run::chooseLearnerSettings(service::loadConfig(choosingConfig(), {}), one)));
  EXPECT_FALSE(plain.contains("learner"));
  EXPECT_FALSE(plain.at("tried")[0].contains("episodes"));
  // ARS that learns nothing (a learning rate of 0) against pg's large Rprop steps: pg.
  const auto frozen = service::loadConfig(
      choosingConfig(), {"learner.choose=[{ learner = \"ars\", n_delta = 2, learning_rate = 0 }, "
                         "{ rprop = \"large\" }]"});
  const auto b = run::chooseLearnerSettings(frozen, one);
  ASSERT_GT(b.means[1], b.means[0]);
  EXPECT_EQ(run::withLearnerChoice(frozen, b).learner, "pg");
}

TEST(LearnerChoice, ARunWithAnotherLearnerChosenWritesItAndResumes) {
  const auto dir = freshDir("choose-ars-run");
  // choosingConfig() with kArsAlternative in the file: a resume reads the config as it is.
  const auto request = choosingRun("choose-ars.toml", std::string(kArsAlternative).substr(8), dir);
  Said progress;
  const std::atomic<bool> go{false};
  ASSERT_TRUE(service::evolve(request, progress, go).finished);
  const auto written = run::loadExperimentConfig(dir + "/config.toml");
  EXPECT_EQ(written.learner, "ars");
  EXPECT_FALSE(run::choosesLearner(written));
  EXPECT_EQ(written.validation.confirmParams.at("updates"), "10");
  const auto runJson = nlohmann::json::parse(readText(dir + "/run.json"));
  EXPECT_EQ(runJson.at("learner_choice").at("learner"), "ars");
  EXPECT_NE(progress.said.find("chosen on this task: ars with"), std::string::npos)
      << progress.said;
  EXPECT_TRUE(resumeFinishes(dir, request.config));
  EXPECT_EQ(run::loadExperimentConfig(dir + "/config.toml").learner, "ars");
}

TEST(LearnerChoice, AssessMayChooseAnotherLearner) {
  auto request = rawAssessment();
  request.overrides = {kArsAlternative};
  request.budget = 8;  // pg's updates: 45 episodes, ARS's 10 iterations.
  std::string printed;
  const auto result = service::assess(request, [&](const std::string& t) { printed += t; });
  EXPECT_EQ(result.config.learner, "ars");
  EXPECT_EQ(result.config.assessParams.at("updates"), "10");
  EXPECT_NE(printed.find("runs on cartpole (ars)"), std::string::npos) << printed;
}

TEST(LearnerChoice, BadCandidateLearnersAreErrorsNamingThem) {
  // Each second alternative (after { rprop = "small" }) and what its error must say.
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases{
      {"{ learner = \"arz\" }",
       {"learner.choose[1].learner", "unknown learner 'arz'", "did you mean 'ars'"}},
      {"{ learner = \"ars\", n_delt = 2 }",
       {"learner.choose[1].n_delt", "learner ars", "did you mean 'n_delta'"}},
      {"{ learner = \"ars\", rprop = \"large\" }", {"learner.choose[1].rprop", "learner ars"}},
      {"{ learner = \"ars\", updates = 5 }", {"learner.choose[1].updates", "gives no budget"}},
      {"{ learner = \"ars\", n_delta = 2, n_top = 3 }",
       {"learner.choose[1]", "n_top must be at most n_delta"}},
      {"{ learner = \"lpi\" }", {"learner.choose[1].learner", "cannot learn on"}},
  };
  for (const auto& [alternative, said] : cases) {
    const auto error = refusal(
        {"learner.choose={}", "learner.choose=[{ rprop = \"small\" }, " + alternative + "]"});
    for (const auto& text : said) {
      EXPECT_NE(error.find(text), std::string::npos) << alternative << " -> " << error;
    }
  }
  const auto values = refusal({"learner.choose.learner=[\"ars\"]"});
  EXPECT_NE(values.find("learner.choose.learner"), std::string::npos) << values;
  EXPECT_NE(values.find("in an alternative"), std::string::npos) << values;
}

}  // namespace
}  // namespace gpfd::testing

namespace gpfd::testing {
namespace {

// pg's natural steps of a KL of 1e-12 learn nothing (the original variables score as no
// learning); ARS with 2 directions, tried only then (learner.choose_fallback), learns.
const char* kFrozenPgOnly = "learner.choose=[{ step = \"natural\", kl = 1e-12 }]";
const char* kArsFallback =
    "learner.choose_fallback=[{ learner = \"ars\", n_delta = 2, learning_rate = 0.1, "
    "greedy_last = true }]";

TEST(LearnerChoice, WhereNoListedCandidateLearnsTheFallbackIsTriedAndChosen) {
  run::ThreadTrialRunner threads(2);
  const auto frozen = service::loadConfig(choosingConfig(), {kFrozenPgOnly});
  ASSERT_TRUE(run::chooseLearnerSettings(frozen, threads).nothingLearns);
  const auto config = service::loadConfig(choosingConfig(), {kFrozenPgOnly, kArsFallback});
  const auto choice = choiceOnAnyThreads(config);
  ASSERT_EQ(choice.candidates.size(), 2u);
  EXPECT_EQ(choice.fallbacksFrom, 1u);
  EXPECT_EQ(choice.learners, (std::vector<std::string>{"pg", "ars"}));
  EXPECT_FALSE(choice.nothingLearns);
  EXPECT_EQ(choice.chosen, 1u);
  const auto chosen = run::withLearnerChoice(config, choice);
  EXPECT_EQ(chosen.learner, "ars");
  EXPECT_TRUE(chosen.learnerFallbacks.empty());
  const auto json = nlohmann::json::parse(run::learnerChoiceJson(choice));
  EXPECT_EQ(json.at("fallback_from"), 1);
  EXPECT_EQ(json.at("learner"), "ars");
  EXPECT_NE(run::learnerChoiceText(choice).find("among learner.choose_fallback's"),
            std::string::npos);
  // A listed candidate that learns: the fallback is not tried, and the choice's JSON is as
  // without one.
  const auto learning = service::loadConfig(choosingConfig(), {kArsFallback});
  const auto plain = run::chooseLearnerSettings(learning, threads);
  EXPECT_EQ(plain.candidates.size(), 2u);  // rprop small and large.
  EXPECT_EQ(plain.fallbacksFrom, 0u);
  EXPECT_EQ(run::learnerChoiceJson(plain),
            run::learnerChoiceJson(
                run::chooseLearnerSettings(service::loadConfig(choosingConfig(), {}), threads)));
  // A fallback that learns nothing either (a learning rate of 0, its zero weights scored): the
  // run stops as before.
  const auto still = service::loadConfig(
      choosingConfig(),
      {kFrozenPgOnly,
       "learner.choose_fallback=[{ learner = \"ars\", learning_rate = 0, greedy_last = true }]"});
  const auto none = run::chooseLearnerSettings(still, threads);
  EXPECT_EQ(none.fallbacksFrom, 1u);
  EXPECT_TRUE(none.nothingLearns);
}

// A run that fell back writes the fallback's learner into config.toml and run.json, and resumes
// against the config that chose it.
TEST(LearnerChoice, ARunThatFellBackWritesItAndResumes) {
  const auto dir = freshDir("choose-fallback-run");
  const auto request = choosingRun(
      "choose-fallback.toml",
      std::string(kFrozenPgOnly).substr(8) + "\n" + std::string(kArsFallback).substr(8), dir);
  Said progress;
  const std::atomic<bool> go{false};
  ASSERT_TRUE(service::evolve(request, progress, go).finished);
  EXPECT_EQ(run::loadExperimentConfig(dir + "/config.toml").learner, "ars");
  const auto runJson = nlohmann::json::parse(readText(dir + "/run.json"));
  EXPECT_EQ(runJson.at("learner_choice").at("fallback_from"), 1);
  EXPECT_NE(progress.said.find("(1 more where none learns)"), std::string::npos) << progress.said;
  EXPECT_TRUE(resumeFinishes(dir, request.config));
}

// Where the fallback would pass the allowance, at the listed candidates' cost, it is not tried,
// and the stop says so.
TEST(LearnerChoice, AFallbackThatWouldPassTheAllowanceIsNotTried) {
  const auto config = service::loadConfig(choosingConfig(), {kFrozenPgOnly, kArsFallback});
  SlowTrialRunner slow(2, 8);  // The one-update and first trainings fast, then 1 s each.
  // The listed candidate: its pairs (1 s more) within 1.5 s; twice that passes it.
  const auto choice = run::chooseLearnerSettings(config, slow, 1.5, 1);
  EXPECT_EQ(choice.cut, run::LearnerChoice::Cut::None);
  EXPECT_TRUE(choice.fallbacksCut);
  EXPECT_EQ(choice.fallbacksFrom, 0u);
  EXPECT_TRUE(choice.nothingLearns);
  EXPECT_NE(run::nothingLearnsText(choice).find("learner.choose_fallback was not tried"),
            std::string::npos);
}

TEST(LearnerChoice, BadFallbacksAreErrorsThatNameThem) {
  const auto refused = [](const std::vector<std::string>& overrides) {
    try {
      service::loadConfig(choosingConfig(), overrides);
    } catch (const InputError& e) {
      return std::string(e.what()) + " @ " + e.where();
    }
    return std::string("accepted");
  };
  EXPECT_NE(
      refused({"learner.choose_fallback=[{ learner = \"arz\" }]"}).find("unknown learner 'arz'"),
      std::string::npos);
  EXPECT_NE(refused({"learner.choose_fallback=[{ learner = \"ars\", n_delt = 2 }]"})
                .find("learner.choose_fallback[0]"),
            std::string::npos);
  EXPECT_NE(refused({"learner.choose_fallback={ learner = \"ars\" }"})
                .find("learner.choose_fallback must be an array of tables"),
            std::string::npos);
  // A value given over the choice leaves no choice, and so no fallback.
  const auto given =
      service::loadConfig(choosingConfig(), {"learner.choose={ rprop = \"small\" }", kArsFallback});
  EXPECT_EQ(given.learnerFallbacks.size(), 1u);
  const auto none =
      service::loadConfig(choosingConfig(), {"learner.params.rprop=small", kArsFallback});
  EXPECT_FALSE(run::choosesLearner(none));
  EXPECT_TRUE(none.learnerFallbacks.empty());
}

}  // namespace
}  // namespace gpfd::testing
