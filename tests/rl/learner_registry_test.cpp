// The learner registry: the built-in learners by name, their parameters declared once, what they
// need from an environment, and training through the registry equal to calling the algorithms.
#include <gtest/gtest.h>

#include <algorithm>

#include "gpfd/env/tetris.hpp"
#include "gpfd/rl/game_afterstates.hpp"
#include "gpfd/rl/lambda_policy_iteration.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/rl/policy_gradient.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::rl {
namespace {

const LearnerRegistry& learners() { return LearnerRegistry::global(); }

std::string refusal(const std::string& learner, const Params& params) {
  try {
    learners().make(learner, params);
  } catch (const InputError& e) {
    return e.message();
  }
  return "accepted";
}

void expectSameCurves(const LearningCurve& a, const LearningCurve& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].meanReturn, b.points[i].meanReturn) << i;
    EXPECT_EQ(a.points[i].steps, b.points[i].steps) << i;
  }
  EXPECT_EQ(a.weights.values, b.weights.values);
}

TEST(LearnerRegistry, KnowsTheBuiltInLearnersAndTheirDeclarations) {
  const auto registered = learners().names();
  for (const char* name : {"ars", "lpi", "pg"}) {
    EXPECT_NE(std::find(registered.begin(), registered.end(), name), registered.end()) << name;
  }
  EXPECT_EQ(learners().info("pg").budgetParam, "updates");
  EXPECT_EQ(learners().info("lpi").budgetParam, "iterations");
  for (const auto& name : learners().names()) {
    const auto& info = learners().info(name);
    const auto names = paramNames(info.params);
    EXPECT_NE(std::find(names.begin(), names.end(), info.budgetParam), names.end()) << name;
    for (const auto& spec : info.params) {
      EXPECT_FALSE(spec.range.empty()) << name << "." << spec.name;
      EXPECT_FALSE(spec.meaning.empty()) << name << "." << spec.name;
    }
    // Every declared default is a value the learner takes back.
    Params defaults;
    for (const auto& spec : info.params) defaults[spec.name] = spec.defaultValue;
    EXPECT_EQ(refusal(name, defaults), "accepted") << name;
  }
  EXPECT_THROW(learners().info("sarsa"), InputError);
}

TEST(LearnerRegistry, RefusesUnknownParametersAndBadValuesByName) {
  EXPECT_EQ(refusal("pg", {{"iterations", "3"}}).rfind("pg has no parameter 'iterations'", 0), 0u);
  EXPECT_EQ(refusal("pg", {{"updates", "-1"}}),
            "updates must lie in [0, 1000000], got -1 (pg.updates)");
  EXPECT_EQ(refusal("pg", {{"rprop", "huge"}}),
            "rprop must be one of large | small, got 'huge' (pg.rprop)");
  EXPECT_EQ(refusal("lpi", {{"weights", "1,x"}}), "'x' is not a finite number (lpi.weights)");
  EXPECT_EQ(refusal("lpi", {{"start", "known"}, {"weights", "1,2"}}),
            "give either start=known or weights, not both (lpi.start)");
}

TEST(LearnerRegistry, SaysWhatALearnerCannotLearnOn) {
  auto cartpole = env::Registry::global().make("cartpole");
  auto tetris = env::Registry::global().make("tetris");
  EXPECT_NO_THROW(learners().checkSuitable("pg", *cartpole));
  EXPECT_NO_THROW(learners().checkSuitable("lpi", *tetris));
  try {
    learners().checkSuitable("lpi", *cartpole);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("learner lpi cannot learn on cartpole"),
              std::string::npos);
  }
  EXPECT_THROW(learners().checkSuitable("pg", *tetris), InputError);
}

TEST(LearnerRegistry, PolicyGradientThroughTheRegistryIsTheAlgorithm) {
  auto env = env::Registry::global().make("cartpole", {{"max_steps", "200"}});
  const features::RawFeatureMap map(env->stateDim());
  const auto learner = learners().make("pg", {{"updates", "4"}, {"rprop", "small"}, {"std", "1"}});
  PolicyGradientConfig config;
  config.updates = 4;
  config.rprop = RpropConfig::paperSmall();
  config.policy.initialStd = 1.0;
  Rng a(7), b(7);
  int rows = 0;
  const auto viaRegistry = learner->train(*env, map, a, [&](const CurvePoint&) { ++rows; });
  const auto direct = trainPolicyGradient(*env, map, config, b);
  expectSameCurves(viaRegistry, direct);
  EXPECT_EQ(rows, 5);
  Rng c(9), d(9);
  const auto evaluation = learner->evaluate(*env, map, direct.weights, 3, c);
  const auto expected = evaluatePolicy(*env, map, direct.weights, config, 3, true, d);
  EXPECT_EQ(evaluation.meanReturn, expected.meanReturn);
  EXPECT_EQ(evaluation.episodes, 3);
}

TEST(LearnerRegistry, LambdaPolicyIterationStartsFromTheKnownWeightsWhenAsked) {
  const Params layout{{"state", "bertsekas"}};
  auto env = env::Registry::global().make("tetris", layout);
  const features::RawFeatureMap raw(env->stateDim());
  const Params settings{{"iterations", "1"}, {"games", "3"}, {"max_moves", "200"}};
  Params known = settings;
  known["start"] = "known";
  Rng a(3), b(3);
  const auto viaStart = learners().make("lpi", known)->train(*env, raw, a);

  env::Tetris tetris(env::TetrisConfig::fromParams(layout));
  GameAfterstateProblem problem(tetris, tetris);
  LambdaPolicyIterationConfig config;
  config.iterations = 1;
  config.gamesPerIteration = 3;
  config.maxMovesPerGame = 200;
  config.initialWeights = tetris.knownValueWeights();
  config.initialWeights.push_back(0.0);  // The bias feature.
  const auto direct = trainLambdaPolicyIteration(problem, raw, config, b);
  expectSameCurves(viaStart, direct);

  // Only with the raw state as features, and only where weights are known.
  const features::ConcatFeatureMap twice({std::make_shared<features::RawFeatureMap>(raw),
                                          std::make_shared<features::RawFeatureMap>(raw)});
  EXPECT_THROW(learners().make("lpi", known)->train(*env, twice, a), InputError);
  auto paper = env::Registry::global().make("tetris");
  const features::RawFeatureMap paperRaw(paper->stateDim());
  EXPECT_THROW(learners().make("lpi", known)->train(*paper, paperRaw, a), InputError);
}

}  // namespace
}  // namespace gpfd::rl
