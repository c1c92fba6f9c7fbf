// The one-standard-error rule (validation.parsimony_se) end to end: what a run confirms and
// returns is chooseWinner's choice under the run's rule, on fresh runs and on resumed ones.
#include <gtest/gtest.h>

#include "cli_helpers.hpp"
#include "gpfd/run/checkpoint.hpp"
#include "gpfd/run/validation.hpp"

namespace gpfd::testing {
namespace {

constexpr std::size_t kCartPoleDim = 4;
const std::string kRule = " --set validation.parsimony_se=100";

// The run's validation stage as its checkpoint holds it.
run::ValidationState validationOf(const std::string& dir) {
  return run::parseCheckpoint(readText(dir + "/checkpoint.json"), dir).validation;
}

// Whether the run in `dir` confirmed the rule's choice; `simplified` counts the runs where that
// choice is not the best mean.
void expectTheRulesChoiceConfirmed(const std::string& dir, int& simplified) {
  const auto v = validationOf(dir);
  const std::size_t chosen = run::chooseWinner(v.sets, kCartPoleDim, 100.0);
  EXPECT_EQ(v.confirmation.key, v.sets[chosen].key) << dir;
  simplified += chosen != run::chooseWinner(v.sets, kCartPoleDim) ? 1 : 0;
}

TEST(Parsimony, RunsConfirmTheSimplestPartOfTheirBest) {
  int simplified = 0;
  for (int seed = 1; seed <= 4; ++seed) {
    const auto dir = freshDir("parsimony-" + std::to_string(seed));
    const auto r = runGpfd("evolve " + tinyEvolveConfig("tiny-parsimony", seed) + " --quiet" +
                           kRule + " --out " + dir);
    ASSERT_EQ(r.status, 0) << r.output;
    expectTheRulesChoiceConfirmed(dir, simplified);
  }
  EXPECT_GT(simplified, 0) << "no run where the rule changed the choice: the test shows nothing";
}

// A resumed run reads the rule from its stored config (the checkpoint does not hold it).
TEST(Parsimony, AResumedRunKeepsTheRule) {
  int simplified = 0;
  const auto dir = freshDir("parsimony-resumed");
  ASSERT_EQ(runGpfd("evolve " + tinyEvolveConfig("tiny-parsimony", 1) + " --quiet" + kRule +
                    " --generations 3 --out " + dir)
                .status,
            0);
  ASSERT_EQ(runGpfd("evolve --quiet --resume " + dir + " --generations 6").status, 0);
  expectTheRulesChoiceConfirmed(dir, simplified);
  EXPECT_EQ(simplified, 1) << "seed 1's best mean is no longer simplified: the test shows nothing";
}

}  // namespace
}  // namespace gpfd::testing
