// Plug-ins: `gpfd --plugin FILE` and a config's `plugins` key load environments and learners that
// a shared library registers (tests/data/plugin/test_plugin.cpp: "walk" and "hill"); every
// command then reaches them by name; bad plug-ins are refused with exit code 2.
#include <gtest/gtest.h>

#include <algorithm>

#include "cli_helpers.hpp"

namespace gpfd::testing {
namespace {

const std::string kPlugin = std::string("--plugin ") + GPFD_TEST_PLUGIN;

TEST(Plugin, RegistersItsEnvironmentAndLearner) {
  const auto envs = runGpfd(kPlugin + " envs");
  ASSERT_EQ(envs.status, 0) << envs.output;
  EXPECT_NE(envs.output.find("walk: a point on a line"), std::string::npos);
  EXPECT_NE(envs.output.find("start = 1  in [-10, 10]"), std::string::npos);
  const auto learners = runGpfd("learners " + kPlugin);  // Anywhere on the line.
  ASSERT_EQ(learners.status, 0) << learners.output;
  EXPECT_NE(learners.output.find("hill: hill climbing"), std::string::npos);
  EXPECT_NE(runGpfd(kPlugin + " train --help").output.find("hill: updates, noise"),
            std::string::npos);
}

TEST(Plugin, ItsLearnerTrainsOnItsEnvironment) {
  const auto dir = freshDir("plugin-train");
  const auto r = runGpfd(kPlugin + " train walk --learner hill --param updates=3 --param start=2" +
                         " --quiet --eval 2 --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string csv = readText(dir + "/curve.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5) << csv;  // Header and rows 0..3.
  EXPECT_NE(readText(dir + "/weights.json").find("\"learner\": \"hill\""), std::string::npos);
  // The built-in learner on the plug-in's environment, and the other way round is refused.
  EXPECT_EQ(runGpfd(kPlugin + " train walk --param updates=2 --quiet --force --out " + dir).status,
            0);
  const auto refused = runGpfd(kPlugin + " train tetris --learner hill --out " + dir);
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.output.find("learner hill cannot learn on tetris"), std::string::npos)
      << refused.output;
}

TEST(Plugin, LoadsFromTheConfigKeyForEvolveAndItsResume) {
  const auto config = writeText(
      "plugin-walk.toml", "name = \"walk\"\nplugins = [\"" + std::string(GPFD_TEST_PLUGIN) + R"("]
[env]
name = "walk"
[learner]
name = "pg"
params = { updates = 3, episodes = 4 }
[gp]
population = 6
generations = 2
)");
  const auto dir = freshDir("plugin-evolve");
  const auto r = runGpfd("evolve " + config + " --quiet --threads 1 --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(readText(dir + "/config.toml").find(GPFD_TEST_PLUGIN), std::string::npos);
  // A results directory is data, not code: its config's plug-ins load only when given again.
  for (const std::string& command : {"evolve --resume " + dir + " --generations 3 --quiet",
                                     "fitness-noise " + dir + " --pairs 1 --replications 2"}) {
    const auto refused = runGpfd(command);
    EXPECT_EQ(refused.status, 2) << command << "\n" << refused.output;
    EXPECT_NE(refused.output.find("the config names the plug-in " + std::string(GPFD_TEST_PLUGIN) +
                                  ", which is not loaded"),
              std::string::npos)
        << command << "\n"
        << refused.output;
  }
  // Its front is shown as the run left it, without the plug-in: nothing is run.
  const auto front = runGpfd("features show " + dir + " --front");
  EXPECT_EQ(front.status, 0) << front.output;
  const auto resumed = runGpfd(kPlugin + " evolve --resume " + dir + " --generations 3 --quiet");
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_EQ(runGpfd("evolve " + config + " --set plugins=[] --quiet --out " + dir + "x").status, 2);
}

TEST(Plugin, IsLoadedOnceAndBadOnesAreRefused) {
  EXPECT_EQ(runGpfd(kPlugin + " " + kPlugin + " envs").status, 0);
  const auto missing = runGpfd("--plugin /nonexistent/libx.so envs");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("error: no such plug-in file (/nonexistent/libx.so)"),
            std::string::npos)
      << missing.output;
  const auto notElf = runGpfd("--plugin " + writeText("not-a-plugin.so", "text") + " envs");
  EXPECT_EQ(notElf.status, 2);
  EXPECT_NE(notElf.output.find("error: cannot load the plug-in"), std::string::npos);
  EXPECT_EQ(runGpfd("envs --plugin").status, 2);
  const auto without = runGpfd("train walk --quiet");
  EXPECT_EQ(without.status, 2);
  EXPECT_NE(without.output.find("unknown environment 'walk'"), std::string::npos);
}

}  // namespace
}  // namespace gpfd::testing
