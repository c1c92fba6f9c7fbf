#include "gpfd/run/validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gpfd/expr/parse.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/method_verdict.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {
namespace {

const expr::VariableNames kNames{"x", "dx", "th", "dth"};

// A set of the features `features` lists, separated by ';' (none: the original variables).
ValidatedSet set(const std::string& features, std::vector<double> scores) {
  ValidatedSet s;
  for (std::size_t from = 0; from < features.size();) {
    const std::size_t end = std::min(features.find(';', from), features.size());
    s.genome.addFeature(expr::parseInfix(features.substr(from, end - from), kNames));
    from = end + 1;
  }
  if (!features.empty()) s.key = gp::canonicalKey(s.genome);
  s.scores = std::move(scores);
  return s;
}

TEST(Validation, TheHallOfFameIsTheBestPenalisedMeans) {
  std::map<std::string, gp::FitnessRecord> cache;
  const auto key = [](const std::string& f) {
    expr::Genome g;
    g.addFeature(expr::parseInfix(f, kNames));
    return gp::canonicalKey(g);
  };
  cache[key("x")] = {10.0, 5};
  cache[key("sin(th) * dth + dx")] = {10.4, 10};  // 6 nodes: 10.4 - 0.6 = 9.8.
  cache[key("th")] = {9.95, 5};
  cache[key("dth")] = {-INFINITY, 5};
  cache[key("0")] = {12.0, 5};  // A placeholder alone (run/redundancy.hpp) never enters.
  const auto hof = hallOfFame(cache, 2, 0.1);
  ASSERT_EQ(hof.size(), 2u);
  EXPECT_EQ(hof[0].key, key("x"));
  EXPECT_DOUBLE_EQ(hof[0].fitness, 10.0 - 0.1);
  EXPECT_EQ(hof[1].key, key("th"));
  EXPECT_EQ(hallOfFame(cache, 10, 0.1).size(), 3u);  // Nor does the diverged genome.
}

TEST(Validation, TheBestMeanWinsAndTheOriginalWinsTies) {
  std::vector<ValidatedSet> sets{set("", {1, 2, 3}), set("x", {2, 2, 2}), set("th", {1, 3, 2})};
  EXPECT_EQ(chooseWinner(sets, 4), 1u);  // Means 2 = 2 = 2: the smallest, first in order.
  sets[1].genome.addFeature(expr::parseInfix("dx * dx * dx", kNames));  // Now 6 nodes.
  sets[2].genome.addFeature(expr::parseInfix("dx * dx * dx", kNames));
  EXPECT_EQ(chooseWinner(sets, 4), 0u);  // Then the original (4 nodes) is the smallest.
  sets.push_back(set("dx", {3, 3, 3}));
  EXPECT_EQ(chooseWinner(sets, 4), 3u);
  sets[0].scores = {5, 5, 5};
  EXPECT_EQ(chooseWinner(sets, 4), 0u);
  EXPECT_EQ(originalIndex(sets), 0u);
}

// The one-standard-error rule keeps a feature only where the seeds show it adds something: the
// best mean gives way to the simplest of its own parts within parsimonySe standard errors.
TEST(Validation, TheSimplestPartWithinOneStandardErrorWins) {
  std::vector<ValidatedSet> sets{
      set("", {1, 2, 3}),
      set("x * th ; dx", {2.9, 3.0, 3.1}),        // The best mean, 3, SE 0.0577.
      set("dx ; x * th ; th", {2.9, 2.9, 3.05}),  // Not a part: it has a feature more.
      set("x * th", {2.95, 3.0, 3.0}),            // A part, 2.983.
      set("dx", {1, 1, 1}),                       // A part, far below.
      set("th", {3.0, 2.98, 2.99})};              // Within the SE and smaller, but not a part.
  EXPECT_EQ(chooseWinner(sets, 4), 1u);           // Off: the best mean.
  EXPECT_EQ(chooseWinner(sets, 4, 1.0), 3u);
  EXPECT_EQ(chooseWinner(sets, 4, 0.2), 1u);  // 2.983 is below 3 - 0.2 SE.
  sets[3].scores = {2.8, 2.8, 2.8};
  EXPECT_EQ(chooseWinner(sets, 4, 1.0), 1u);
  sets[0].scores = {4, 4, 4};  // The original variables win: nothing to simplify.
  EXPECT_EQ(chooseWinner(sets, 4, 1.0), 0u);

  // What the run returns and confirms follows the state's rule.
  ValidationState state;
  state.sets = {set("", {1, 2, 3}), set("x ; dx", {2.9, 3.0, 3.1}), set("x", {3.0, 2.9, 3.0})};
  EXPECT_EQ(returnedIndex(state, 4), 1u);
  state.parsimonySe = 1.0;
  EXPECT_EQ(chooseWinner(state, 4), 2u);
  EXPECT_EQ(returnedIndex(state, 4), 2u);
}

TEST(Validation, TablesListEverySetAndTheFront) {
  const std::vector<ValidatedSet> sets{set("", {1, 2, 3}), set("x", {2, 2.5, 3}),
                                       set("sin(th) * dth", {2.5, 3, 3.5}),
                                       set("th * th * th * th", {0, 1, 2})};
  const auto csv = formatValidationCsv(sets, 2, kNames);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_NE(csv.find("1,hall-of-fame,-1,4,1"), std::string::npos);  // Best first, selected.
  // The front: x (1 node) beats every smaller set; sin(th) * dth (4 nodes) beats x; the
  // original (4 nodes, worse) and the 7-node set (worse) are not on it.
  const auto front = formatFrontCsv(sets, kNames);
  EXPECT_EQ(std::count(front.begin(), front.end(), '\n'), 3);
  EXPECT_NE(front.find("\"x\""), std::string::npos);
  EXPECT_NE(front.find("\"sin(th) * dth\""), std::string::npos);
  // Its scores are the selection's (the validation means), and its header says so.
  EXPECT_EQ(front.substr(0, front.find('\n')),
            "size,features,selection,selection_se,seeds,p_vs_original,set,expressions");
  const auto table = formatFrontTable(sets, kNames);
  EXPECT_NE(table.substr(0, table.find('\n')).find("selection (mean +- SE)"), std::string::npos)
      << table;
}

TEST(Validation, ConfirmationDecidesAndIsWhatIsReported) {
  ValidationState state;
  state.sets = {set("", {1, 2, 3}), set("x", {3, 3, 3}), set("th", {1, 1, 1})};
  EXPECT_EQ(returnedIndex(state, 4), 1u);  // Not confirmed: the validation winner.
  EXPECT_FALSE(reportedScores(state, 4).confirmed);
  EXPECT_EQ(reportedScores(state, 4).returned, &state.sets[1].scores);

  state.confirmation = {state.sets[1].key, {2, 2.5, 3}, {2, 2, 2}, {}, 0.05};  // Holds: +0.5.
  EXPECT_EQ(returnedIndex(state, 4), 1u);
  const auto held = reportedScores(state, 4);
  EXPECT_TRUE(held.confirmed);
  EXPECT_EQ(held.returned, &state.confirmation.winner);
  EXPECT_EQ(held.original, &state.confirmation.original);

  state.confirmation.winner = {2, 2, 1.5};  // Does not hold: the original variables return.
  EXPECT_FALSE(state.confirmation.held());
  EXPECT_EQ(returnedIndex(state, 4), 0u);
  EXPECT_EQ(reportedScores(state, 4).returned, &state.confirmation.original);
  const auto csv = formatConfirmationCsv(state, kNames);
  EXPECT_NE(csv.find("validation-winner,1.8333"), std::string::npos) << csv;
  EXPECT_NE(csv.find("original,2,0,0,3,0,1,1,"), std::string::npos) << csv;

  state.sets.push_back(set("dx", {5, 5, 5}));  // A new winner: the old confirmation is stale.
  EXPECT_EQ(returnedIndex(state, 4), 3u);
  EXPECT_FALSE(reportedScores(state, 4).confirmed);
}

// The no-learning reference (a policy that ignores the state) is never a candidate; a discovered
// winner not significantly better than it is not returned; the original variables significantly
// worse than it mean the learner harms.
TEST(Validation, NoLearningIsAReferenceThatADiscoveryMustBeat) {
  ValidationState state;
  state.sets = {set("", {1, 2, 3, 1, 2, 3}), set("x", {5, 6, 7, 5, 6, 7}),
                set("th", {0, 0, 0, 0, 0, 0})};
  EXPECT_EQ(returnedIndex(state, 4), 1u);  // Not scored (a run made before it): as before.
  EXPECT_FALSE(noLearningVerdict(state, 4).scored);
  state.noLearning = {5, 6.1, 6.9, 5.1, 5.9, 7};  // Level with the winner, far above the original.
  EXPECT_EQ(chooseWinner(state.sets, 4), 1u);     // Never a candidate itself.
  EXPECT_EQ(returnedIndex(state, 4), 0u);
  const auto verdict = noLearningVerdict(state, 4);
  EXPECT_TRUE(verdict.scored);
  EXPECT_TRUE(verdict.learnerHarms);
  EXPECT_TRUE(verdict.winnerNoBetter);
  EXPECT_EQ(reportedScores(state, 4).noLearning, &state.noLearning);

  // validation.csv: the existing rows as without it, then the reference, unranked.
  const auto without = formatValidationCsv(state.sets, 0, kNames);
  const auto with = formatValidationCsv(state.sets, 0, kNames, state.noLearning);
  ASSERT_EQ(with.substr(0, without.size()), without);
  EXPECT_EQ(with.substr(without.size()).rfind(",no-learning,-1,1,1,nan,0,", 0), 0u) << with;
  EXPECT_EQ(std::count(with.begin(), with.end(), '\n'), 5);

  state.noLearning = {1, 1.5, 1, 1.2, 1, 1};  // Below both: the winner is a discovery.
  EXPECT_EQ(returnedIndex(state, 4), 1u);
  EXPECT_FALSE(noLearningVerdict(state, 4).learnerHarms);
  EXPECT_FALSE(noLearningVerdict(state, 4).winnerNoBetter);

  // Confirmed: the winner holds against the original variables but is level with no learning.
  state.confirmation = {state.sets[1].key, {2, 2.5, 3}, {1, 1, 1.5}, {2, 2.5, 3}, 0.045};
  EXPECT_TRUE(state.confirmation.held());
  EXPECT_FALSE(state.confirmation.beatsNoLearning());
  EXPECT_EQ(returnedIndex(state, 4), 0u);
  const auto reported = reportedScores(state, 4);
  EXPECT_EQ(reported.returned, &state.confirmation.original);
  EXPECT_EQ(reported.noLearning, &state.confirmation.noLearning);
  EXPECT_TRUE(noLearningVerdict(state, 4).winnerNoBetter);
  const auto csv = formatConfirmationCsv(state, kNames);
  EXPECT_NE(csv.find("validation-winner,2.5,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\noriginal,1.1666666666666667,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",1,\"original variables\"\nno-learning,2.5,"), std::string::npos) << csv;
  // Clearly above it at the level of the last look: returned.
  state.confirmation.noLearning = {0, 0.4, 1.1};
  EXPECT_TRUE(state.confirmation.beatsNoLearning());
  EXPECT_EQ(returnedIndex(state, 4), 1u);
}

TEST(Validation, TheReturnedFileLeavesPlaceholdersOut) {
  auto config = loadExperimentConfig(std::string(GPFD_SOURCE_DIR) + "/configs/cartpole-quick.toml");
  config.withOriginal = true;
  config.normalise = false;  // The expression as written.
  const LearningTask task(config, LearningTask::Budget::Validation);
  ValidationState state;
  state.sets = {set("", {1, 2, 3}), set("sin(th)", {3, 3, 3})};
  state.sets[1].genome.addFeature(expr::parseInfix("0", kNames));  // As min_features = 2 leaves it.
  state.sets[1].key = gp::canonicalKey(state.sets[1].genome);
  const auto file = returnedFeaturesFile(state, task.prepared(state.sets[1].genome), task);
  ASSERT_EQ(file.genome.featureCount(), 1u);
  EXPECT_EQ(expr::toInfix(file.genome.feature(0), kNames), "sin(th)");
}

// best.features names each score by what it is: `selection` (validation means, biased for the
// winner), `confirmed` (fresh seeds, unbiased), `gp_fitness` (the GP's own), never `validated`;
// its verdict claims a difference only where the paired t-test finds one.
TEST(Validation, TheReturnedFileNamesEachScoreByWhatItIs) {
  auto config = loadExperimentConfig(std::string(GPFD_SOURCE_DIR) + "/configs/cartpole-quick.toml");
  config.normalise = false;
  const LearningTask task(config, LearningTask::Budget::Validation);
  ValidationState state;
  state.sets = {set("", {1, 2, 3}), set("sin(th)", {3, 3, 3.5})};
  state.sets[1].gpFitness = 7.5;
  state.sets[1].gpTrials = 5;

  // Not confirmed: the selection score stands, and +1.167 at p = 0.118 is no difference.
  auto file = returnedFeaturesFile(state, state.sets[1].genome, task);
  EXPECT_EQ(file.meta.count("validated"), 0u);
  EXPECT_EQ(file.meta.count("validated_by"), 0u);
  EXPECT_EQ(file.meta.count("fitness"), 0u);
  EXPECT_EQ(file.meta.count("confirmed"), 0u);
  EXPECT_EQ(file.meta.at("selection"), "3.16667 +- 0.167 (3 trials)");
  EXPECT_EQ(file.meta.at("selection_by").rfind("3 validation seeds", 0), 0u);
  EXPECT_EQ(file.meta.at("original"), "2 +- 0.577 (3 trials)");
  EXPECT_EQ(file.meta.at("gp_fitness"), "7.5");
  EXPECT_EQ(file.meta.at("verdict"),
            "not significantly different from the original variables on the validation seeds "
            "(difference 1.167, paired t-test p = 0.118)");

  // Confirmed: the confirmation's scores stand beside the selection's; +5 at p < 0.001.
  state.confirmation = {state.sets[1].key, {10, 12, 11, 14, 13}, {5, 6, 7, 8, 9}, {}, 0.05};
  file = returnedFeaturesFile(state, state.sets[1].genome, task);
  EXPECT_EQ(file.meta.at("confirmed"), "12 +- 0.707 (5 trials)");
  EXPECT_EQ(file.meta.at("confirmed_by").rfind("5 fresh seeds", 0), 0u);
  EXPECT_EQ(file.meta.at("selection"), "3.16667 +- 0.167 (3 trials)");
  EXPECT_EQ(file.meta.at("original"), "7 +- 0.707 (5 trials)");
  EXPECT_EQ(file.meta.at("verdict").rfind("better than the original variables on the "
                                          "confirmation seeds by 5 (paired t-test p = 0.000",
                                          0),
            0u)
      << file.meta.at("verdict");

  EXPECT_EQ(comparisonVerdict({10, -2.5, 0.5, 0.01}, "B", "the seeds"),
            "worse than B on the seeds by 2.5 (paired t-test p = 0.01)");
}

TEST(MethodVerdict, CountsRunsAndReadsBack) {
  Summary originalFinal{20, 100, 10, 4}, originalArea{20, 50, 5, 2};
  std::vector<RunAssessment> runs;
  for (int r = 1; r <= 8; ++r) {
    RunAssessment a;
    a.run = r;
    a.seed = 100 + r;
    a.returned = r == 8 ? "original" : "discovered";
    a.final = {20, 100.0 + r, 10, 4};
    a.area = {20, 50.0 - r, 5, 2};
    a.finalVsOriginal.welchP = r >= 6 ? 0.01 : 0.5;
    a.areaVsOriginal.welchP = 0.01;
    runs.push_back(a);
  }
  const auto verdict = methodVerdict(runs, originalFinal, originalArea);
  EXPECT_EQ(verdict.betterFinal, 3);
  EXPECT_EQ(verdict.worseArea, 8);
  EXPECT_NEAR(verdict.final.p, 0.0078125, 1e-12);
  Summary readFinal, readArea;
  const auto back = parseMethodCsv(formatMethodCsv(runs, originalFinal, originalArea), "test",
                                   readFinal, readArea);
  ASSERT_EQ(back.size(), 8u);
  EXPECT_EQ(back[7].returned, "original");
  EXPECT_EQ(back[3].final.mean, 104.0);
  EXPECT_EQ(readArea.mean, 50.0);
  const auto again = methodVerdict(back, readFinal, readArea);
  EXPECT_EQ(again.finalDifferences, verdict.finalDifferences);
  EXPECT_EQ(verdictTable(verdict, &again).size(), 3u);
  EXPECT_THROW(parseMethodCsv("run,seed\n1,2\n", "bad.csv", readFinal, readArea), InputError);
  // A file written before the reported score's columns were renamed reads the same.
  std::string before = formatMethodCsv(runs, originalFinal, originalArea);
  const std::string renamed = "reported_n,reported_mean,reported_sd";
  ASSERT_NE(before.find(renamed), std::string::npos);
  before.replace(before.find(renamed), renamed.size(), "validated_n,validated_mean,validated_sd");
  EXPECT_EQ(parseMethodCsv(before, "before.csv", readFinal, readArea).size(), 8u);
}

// The no-learning row of method-NAME.csv reads back, and the verdict names a harmful learner and
// the runs whose discovered set ends no better than no learning.
TEST(MethodVerdict, SaysWhereTheOriginalVariablesOrARunAreNoBetterThanNoLearning) {
  const Summary originalFinal{20, 100, 10, 4}, originalArea{20, 50, 5, 2};
  std::vector<RunAssessment> runs;
  for (int r = 1; r <= 4; ++r) {
    RunAssessment a;
    a.run = r;
    a.returned = r == 4 ? "original" : "discovered";
    a.final = {20, r == 1 ? 150.0 : 131.0, 10, 4};  // Runs 2 and 3 level with no learning.
    a.area = {20, 50, 5, 2};
    runs.push_back(a);
  }
  const NoLearningRow noLearning{{20, 130, 10, 4}, {20, 40, 5, 2}};
  const auto verdict = methodVerdict(runs, originalFinal, originalArea, noLearning);
  EXPECT_TRUE(verdict.noLearningAssessed);
  EXPECT_TRUE(verdict.learnerHarms);
  EXPECT_EQ(verdict.discoveredNoBetter, 2);
  EXPECT_NE(noLearningSentence(verdict).find("The learner harms"), std::string::npos);
  EXPECT_NE(noLearningSentence(verdict).find("2 of 4 runs"), std::string::npos);
  Summary readFinal, readArea;
  std::optional<NoLearningRow> read;
  const auto csv = formatMethodCsv(runs, originalFinal, originalArea, noLearning);
  EXPECT_NE(csv.find("\nno-learning,,,,,,0,0,0,0,0,0,20,130,10,20,40,5,"), std::string::npos)
      << csv;
  EXPECT_EQ(parseMethodCsv(csv, "test", readFinal, readArea, &read).size(), 4u);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->final.mean, 130.0);
  EXPECT_EQ(read->area.stddev, 5.0);
  // Without the reference (files made before it): nothing said.
  EXPECT_FALSE(methodVerdict(runs, originalFinal, originalArea).noLearningAssessed);
  EXPECT_EQ(noLearningSentence(methodVerdict(runs, originalFinal, originalArea)), "");
}

}  // namespace
}  // namespace gpfd::run
