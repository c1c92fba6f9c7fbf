// The lockstep player uses a plug-in's batched form: "drift" of tests/data/plugin/test_plugin.cpp
// declares one in its registry entry and prints at exit how many steps each form made. With
// lockstep, `gpfd train` and `gpfd evolve` (the trials of each fitness evaluation together) step
// every lane through the form, and give the sequential path's results bit for bit.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "../run/cli_helpers.hpp"

namespace gpfd::testing {
namespace {

const std::string kPlugin = std::string("--plugin ") + GPFD_TEST_PLUGIN;

struct Counts {
  long scalar = -1, batched = -1;
};

// What the plug-in printed at exit; -1 each when it printed nothing.
Counts stepCounts(const std::string& output) {
  std::smatch m;
  Counts c;
  if (std::regex_search(
          output, m, std::regex(R"(drift steps: (\d+) by step\(\), (\d+) by the batched form)"))) {
    c.scalar = std::stol(m[1]);
    c.batched = std::stol(m[2]);
  }
  return c;
}

long jsonInteger(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": (\\d+)"))) return -1;
  return std::stol(m[1]);
}

std::string jsonArray(const std::string& json, const std::string& key) {
  const auto from = json.find("\"" + key + "\": [");
  return from == std::string::npos ? "" : json.substr(from, json.find(']', from) - from);
}

TEST(LockstepPlugin, TrainStepsEveryLaneThroughThePluginsBatchedForm) {
  std::string curves[2], weights[2];
  for (const bool lockstep : {true, false}) {
    const auto dir = freshDir(lockstep ? "drift-lockstep" : "drift-sequential");
    const auto r = runGpfd(kPlugin + " train drift --param updates=6 --param episodes=7" +
                           " --param lockstep=" + (lockstep ? "true" : "false") +
                           " --seed 4 --quiet --out " + dir);
    ASSERT_EQ(r.status, 0) << r.output;
    curves[lockstep] = readText(dir + "/curve.csv");
    weights[lockstep] = readText(dir + "/weights.json");
    const long steps = jsonInteger(weights[lockstep], "steps");
    EXPECT_GT(steps, 6 * 7);
    const Counts counts = stepCounts(r.output);
    EXPECT_EQ(counts.scalar, lockstep ? 0 : steps) << r.output;
    EXPECT_EQ(counts.batched, lockstep ? steps : 0) << r.output;
  }
  EXPECT_EQ(curves[true], curves[false]);
  EXPECT_FALSE(jsonArray(weights[true], "values").empty()) << weights[true];
  EXPECT_EQ(jsonArray(weights[true], "values"), jsonArray(weights[false], "values"));
}

TEST(LockstepPlugin, EvolveTrialsUseTheBatchedFormWithTheSameFitness) {
  std::string fingerprints[2];
  for (const bool lockstep : {true, false}) {
    const auto config =
        writeText(std::string("drift-") + (lockstep ? "lockstep" : "sequential") + ".toml",
                  "name = \"drift\"\nplugins = [\"" + std::string(GPFD_TEST_PLUGIN) + R"("]
[env]
name = "drift"
[learner]
name = "pg"
params = { updates = 3, episodes = 4, lockstep = )" +
                      (lockstep ? "true" : "false") + R"( }
[fitness]
trials = 3
[gp]
population = 6
generations = 2
)");
    const auto dir = freshDir(std::string("drift-evolve-") + (lockstep ? "lockstep" : "seq"));
    const auto r = runGpfd("evolve " + config + " --quiet --threads 1 --out " + dir);
    ASSERT_EQ(r.status, 0) << r.output;
    fingerprints[lockstep] =
        withoutSeconds(readText(dir + "/generations.csv")) + readText(dir + "/best.features");
    const Counts counts = stepCounts(r.output);
    if (lockstep) {
      EXPECT_GT(counts.batched, 0) << r.output;
    } else {
      EXPECT_EQ(counts.batched, 0) << r.output;
      EXPECT_GT(counts.scalar, 0) << r.output;
    }
  }
  EXPECT_EQ(fingerprints[true], fingerprints[false]);
}

}  // namespace
}  // namespace gpfd::testing
