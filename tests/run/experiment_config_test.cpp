// Config checks: the operator table gp.operators (the shipped configs give the earlier rates bit
// for bit; bad weights and the removed keys are refused at their place), seeds (any uint64, never
// a negative one, from a file, --set or --seed), the run's name, and unknown keys.
#include "gpfd/run/experiment_config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "cli_helpers.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::run {
namespace {

// The InputError of parsing `text` with `overrides`, as "where: what"; "" when it parses.
std::string refusal(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parseExperimentConfig(text, "c.toml", overrides);
  } catch (const InputError& e) {
    return e.where() + ": " + e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ExperimentConfig, ShippedConfigsGiveTheEarlierOperatorRatesBitForBit) {
  // What crossover = 0.7, list_crossover_share = 0.1666666667 and the weights 2 : 1 : 1 gave.
  const double crossover = 0.7, share = 0.1666666667, mutation = 1.0 - crossover;
  const std::vector<double> earlier{crossover * (1.0 - share), crossover * share,
                                    mutation * 2.0 / 4.0, mutation * 1.0 / 4.0,
                                    mutation * 1.0 / 4.0};
  int configs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(GPFD_SOURCE_DIR "/configs")) {
    if (entry.path().extension() != ".toml") continue;
    // user-env and user-env-ars name no environment of their own: the one a run is given
    // replaces it.
    const bool forAnyEnv = entry.path().stem().string().starts_with("user-env");
    const auto config = loadExperimentConfig(
        entry.path().string(),
        forAnyEnv ? std::vector<std::string>{"env.name=cartpole"} : std::vector<std::string>{});
    const auto p = gp::operatorProbabilities(config.gp);
    for (std::size_t o = 0; o < earlier.size(); ++o) {
      EXPECT_EQ(p[o], earlier[o]) << entry.path() << " operator " << o;
    }
    ++configs;
  }
  EXPECT_GE(configs, 11);
}

TEST(ExperimentConfig, OperatorWeightsFromTheTable) {
  const auto config =
      parseExperimentConfig("[gp]\noperators = { node_mutation = 3, shrinkage = 0 }\n", "c.toml",
                            {"gp.operators.tree_mutation=0.5"});
  EXPECT_EQ(config.gp.operatorWeights.at("node_mutation"), 3.0);
  EXPECT_EQ(config.gp.operatorWeights.at("shrinkage"), 0.0);
  EXPECT_EQ(config.gp.operatorWeights.at("tree_mutation"), 0.5);
  EXPECT_EQ(config.gp.operatorWeights.count("subtree_crossover"), 0u);  // Its default.
  // The resolved config lists every operator's weight and reads back the same probabilities.
  const auto text = formatExperimentConfig(config);
  EXPECT_TRUE(has(text, "subtree_crossover = ")) << text;
  EXPECT_EQ(gp::operatorProbabilities(parseExperimentConfig(text, "resolved").gp),
            gp::operatorProbabilities(config.gp));
}

TEST(ExperimentConfig, BadOperatorWeightsAreRefusedAtTheirPlace) {
  const auto unknown = refusal("[gp.operators]\nnode_mutaton = 1\n");
  EXPECT_TRUE(has(unknown, "c.toml:2:16 gp.operators.node_mutaton: ")) << unknown;
  EXPECT_TRUE(has(unknown, "(did you mean 'node_mutation'?)")) << unknown;
  const auto farOff = refusal("", {"gp.operators.zzz=1"});
  EXPECT_TRUE(has(farOff, "--set gp.operators.zzz: ")) << farOff;
  EXPECT_TRUE(has(farOff, "known: subtree_crossover, feature_list_crossover")) << farOff;
  EXPECT_TRUE(
      has(refusal("[gp.operators]\nshrinkage = -1\n"), "c.toml:2:13 gp.operators.shrinkage"));
  EXPECT_TRUE(has(refusal("[gp.operators]\nshrinkage = inf\n"), "non-negative"));
  EXPECT_TRUE(has(refusal("[gp.operators]\nshrinkage = nan\n"), "non-negative"));
  EXPECT_TRUE(has(refusal("[gp.operators]\nshrinkage = \"1\"\n"), "must be a number"));
  EXPECT_TRUE(has(refusal("[gp]\noperators = 1\n"), "gp.operators must be a table"));
  const auto zero = refusal(
      "[gp.operators]\nsubtree_crossover = 0\nfeature_list_crossover = 0\nnode_mutation = 0\n"
      "tree_mutation = 0\nshrinkage = 0\n");
  EXPECT_TRUE(has(zero, "must not all be zero")) << zero;
}

TEST(ExperimentConfig, TheEarlierOperatorKeysPointToTheTable) {
  for (const std::string key : {"crossover", "list_crossover_share", "node_mutation_weight",
                                "tree_mutation_weight", "shrinkage_weight"}) {
    const auto file = refusal("[gp]\n" + key + " = 0.5\n");
    EXPECT_TRUE(has(file, "c.toml:2:")) << file;
    EXPECT_TRUE(has(file, "gp." + key + " is no longer a key")) << file;
    EXPECT_TRUE(has(file, "gp.operators = { subtree_crossover = ")) << file;
    EXPECT_TRUE(has(refusal("", {"gp." + key + "=0.5"}), "gp.operators = {"));
  }
}

TEST(ExperimentConfig, EverySeedGpfdPrintsIsAccepted) {
  const std::uint64_t big = 10696572954110202655u;  // A run seed of `evolve --runs`.
  EXPECT_EQ(parseExperimentConfig("seed = \"10696572954110202655\"\n", "c.toml").seed, big);
  EXPECT_EQ(parseExperimentConfig("", "c.toml", {"seed=10696572954110202655"}).seed, big);
  EXPECT_EQ(parseExperimentConfig("", "c.toml", {"seed=18446744073709551615"}).seed,
            std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(parseExperimentConfig("seed = 9223372036854775807\n", "c.toml").seed,
            std::uint64_t{9223372036854775807});
  EXPECT_EQ(parseExperimentConfig("seed = 0\n", "c.toml").seed, 0u);
  ExperimentConfig config;
  config.seed = big;
  const auto text = formatExperimentConfig(config);
  EXPECT_TRUE(has(text, "seed = '10696572954110202655'")) << text;
  EXPECT_EQ(parseExperimentConfig(text, "resolved").seed, big);
}

TEST(ExperimentConfig, NegativeOrMalformedSeedsAreRefused) {
  const auto negative = refusal("", {"seed=-5"});
  EXPECT_TRUE(has(negative, "--set seed: seed must be an integer in [0, 18446744073709551615]"))
      << negative;
  EXPECT_TRUE(has(negative, "seed = \"18446744073709551611\"")) << negative;
  EXPECT_TRUE(has(refusal("seed = -1\n"), "c.toml:1:8 seed: ")) << refusal("seed = -1\n");
  EXPECT_TRUE(has(refusal("", {"seed=18446744073709551616"}), "not '18446744073709551616'"));
  EXPECT_TRUE(has(refusal("seed = \"12a\"\n"), "not '12a'"));
  EXPECT_TRUE(has(refusal("seed = \"\"\n"), "seed must be an integer"));
  EXPECT_TRUE(has(refusal("seed = 1.5\n"), "seed must be an integer"));
}

TEST(ExperimentConfig, TheNameIsADirectoryNameInsideResults) {
  for (const std::string bad : {"../../../x", "", ".", "..", ".hidden", "a/b", "a b", "x\\\\y"}) {
    const auto why = refusal("name = \"" + bad + "\"\n");
    EXPECT_TRUE(has(why, "c.toml:1:8 name: name must be letters, digits")) << bad << ": " << why;
  }
  EXPECT_TRUE(has(refusal("", {"name=../x"}), "--set name: "));
  EXPECT_EQ(refusal("name = \"cartpole-quick_2.v1\"\n"), "");
}

TEST(ExperimentConfig, AnUnknownKeyGetsASuggestionOrTheKnownKeys) {
  for (const auto& why : {refusal("[gp]\nnope = 1\n"), refusal("", {"gp.nope=1"})}) {
    EXPECT_TRUE(
        has(why, "unknown key 'gp.nope' (known: distinct_offspring, elitism, generations, "))
        << why;
  }
  for (const auto& why : {refusal("[gp]\npopulaton = 1\n"), refusal("", {"gp.populaton=1"})}) {
    EXPECT_TRUE(has(why, "(did you mean 'population'?)")) << why;
  }
}

// validation.measure: absent, validation scores a trial as GP does and the written config has no
// such key (configs written before it keep their text); given, it scores validation trials only,
// and is written and read back.
TEST(ExperimentConfig, ValidationMeasureScoresValidationTrialsOnly) {
  const std::string path = GPFD_SOURCE_DIR "/configs/cartpole-quick.toml";
  rl::LearningCurve curve;
  for (const double r : {1.0, 2.0, 6.0}) curve.points.push_back({0, 0, 0, r});
  const auto plain = loadExperimentConfig(path);
  EXPECT_FALSE(plain.validation.measure.has_value());
  EXPECT_FALSE(has(formatExperimentConfig(plain), "\nmeasure = 'final'"));
  EXPECT_EQ(LearningTask(plain, LearningTask::Budget::Validation).score(curve), 3.0);
  const auto given = parseExperimentConfig(
      formatExperimentConfig(loadExperimentConfig(path, {"validation.measure=final"})), "c.toml");
  ASSERT_TRUE(given.validation.measure.has_value());
  EXPECT_EQ(*given.validation.measure, TrialMeasure::Final);
  EXPECT_EQ(LearningTask(given, LearningTask::Budget::Validation).score(curve), 6.0);
  EXPECT_EQ(LearningTask(given, LearningTask::Budget::Trial).score(curve), 3.0);
  EXPECT_TRUE(has(refusal("", {"validation.measure=best"}), "validation.measure"));
}

// task_timeout: absent, none and no key written (configs keep their text); seconds or a duration
// text, written as seconds among the root table's keys (where gpfd._deadline reads it) and read
// back; zero, negative or malformed values refused naming the key.
TEST(ExperimentConfig, TaskTimeoutIsSecondsWrittenOnlyWhereSet) {
  const std::string path = GPFD_SOURCE_DIR "/configs/cartpole-quick.toml";
  const auto plain = loadExperimentConfig(path);
  EXPECT_EQ(plain.taskTimeout, 0.0);
  EXPECT_FALSE(has(formatExperimentConfig(plain), "task_timeout"));
  const std::string text = formatExperimentConfig(loadExperimentConfig(path, {"task_timeout=2m"}));
  EXPECT_TRUE(has(text, "\ntask_timeout = 120")) << text;
  EXPECT_LT(text.find("task_timeout"), text.find("\n["));
  EXPECT_EQ(parseExperimentConfig(text, "c.toml").taskTimeout, 120.0);
  for (const char* bad : {"task_timeout=0", "task_timeout=-1", "task_timeout='abc'"}) {
    EXPECT_TRUE(has(refusal("", {bad}), "task_timeout")) << bad << ": " << refusal("", {bad});
  }
}

// The bug as reported: `evolve --seed` refused the seeds `evolve --runs` prints.
TEST(ExperimentConfig, RejectingConstantGenomesNeedsDistinctOffspring) {
  const std::string path = GPFD_SOURCE_DIR "/configs/cartpole-quick.toml";
  try {
    loadExperimentConfig(path, {"genome.reject_constant=true"});
    FAIL() << "accepted genome.reject_constant without gp.distinct_offspring";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gp.distinct_offspring"), std::string::npos);
    EXPECT_NE(e.where().find("reject_constant"), std::string::npos) << e.where();
  }
  const auto both =
      loadExperimentConfig(path, {"genome.reject_constant=true", "gp.distinct_offspring=true"});
  EXPECT_TRUE(both.rejectConstant);
  EXPECT_TRUE(both.gp.distinctOffspring);
  // Written and read back (config.toml of a run, its resume).
  const auto again = parseExperimentConfig(formatExperimentConfig(both), "config.toml");
  EXPECT_TRUE(again.rejectConstant && again.gp.distinctOffspring);
}

// Successive halving's keys: its longest rung is the confirmation's, its middle one needs it on.
TEST(ExperimentConfig, SuccessiveHalvingNeedsAConfirmationAndChecksItsRung) {
  const std::string path = GPFD_SOURCE_DIR "/configs/cartpole-quick.toml";
  const auto refusedFor = [&](const std::vector<std::string>& overrides) {
    try {
      loadExperimentConfig(path, overrides);
    } catch (const InputError& e) {
      return std::string(e.what()) + " @ " + e.where();
    }
    return std::string("accepted");
  };
  EXPECT_TRUE(has(refusedFor({"fitness.promote=0.3", "validation.confirm_seeds=0"}),
                  "fitness.promote needs a confirmation"));
  EXPECT_TRUE(has(refusedFor({"fitness.rung_params.updates=100"}), "set fitness.promote too"));
  EXPECT_TRUE(has(refusedFor({"fitness.promote=0.3", "fitness.rung_params.updatez=100"}),
                  "fitness.rung_params"));
  EXPECT_TRUE(has(refusedFor({"fitness.promote=1"}), "fitness.promote"));
  const auto config =
      loadExperimentConfig(path, {"fitness.promote=0.25", "fitness.rung_params.updates=100"});
  const auto again = parseExperimentConfig(formatExperimentConfig(config), "config.toml");
  EXPECT_EQ(again.gp.promote, 0.25);
  EXPECT_EQ(again.rungParams, (std::map<std::string, std::string>{{"updates", "100"}}));
  // The rungs: the middle one, then the confirmation's training, each with halving off.
  const auto rungs = fitnessRungs(config);
  ASSERT_EQ(rungs.size(), 2u);
  EXPECT_EQ(rungs[0].learnerParams.at("updates"), "100");
  EXPECT_EQ(rungs[0].measure, config.measure);
  EXPECT_EQ(rungs[1].learnerParams.at("updates"), config.validation.confirmParams.at("updates"));
  EXPECT_EQ(rungs[1].measure, config.validation.confirmMeasure);
  for (const auto& rung : rungs) {
    EXPECT_EQ(rung.gp.promote, 0.0);
    EXPECT_NO_THROW(validate(rung));
  }
  EXPECT_TRUE(fitnessRungs(loadExperimentConfig(path)).empty());
}

TEST(ExperimentConfig, EvolveTakesABigSeedAndStoresIt) {
  const auto dir = gpfd::testing::freshDir("big-seed");
  const auto r = gpfd::testing::runGpfd(
      "evolve cartpole-quick --seed 10696572954110202655 --population 4 --generations 1 "
      "--set validation.candidates=0 --quiet --out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(has(gpfd::testing::readText(dir + "/config.toml"), "seed = '10696572954110202655'"));
  const auto negative =
      gpfd::testing::runGpfd("evolve cartpole-quick --set seed=-5 --out " + dir + "-2");
  EXPECT_EQ(negative.status, 2) << negative.output;
}

}  // namespace
}  // namespace gpfd::run
