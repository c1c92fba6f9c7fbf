// What a new user's second trial found (issue "One front door", point 6), checked on the tool as
// a user runs it: interrupted runs, usage errors and results directories.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <thread>

#include "../run/cli_helpers.hpp"

namespace gpfd::testing {
namespace {
namespace fs = std::filesystem;

// Ctrl-C is acknowledged at once, and the features left behind say they are not validated.
TEST(FrontDoor, CtrlCIsAcknowledgedAndTheFeaturesSayTheyAreNotValidated) {
  const auto dir = freshDir("ctrl-c");
  const auto log = ::testing::TempDir() + "/ctrl-c.log";
  const auto run = startGpfd("evolve --generations 200 --threads 1 --out " + dir, log);
  ASSERT_TRUE(waitForFile(dir + "/best.features", 120));
  ::kill(run.pid, SIGINT);
  // The notice comes before the generation ends.
  bool acknowledged = false;
  for (int i = 0; i < 100 && !acknowledged; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    acknowledged = readText(log).find("press Ctrl-C again") != std::string::npos;
  }
  EXPECT_TRUE(acknowledged) << readText(log);
  EXPECT_EQ(run.wait(), 130);
  const auto output = readText(log);
  EXPECT_NE(output.find("NOT validated"), std::string::npos) << output;
  const auto features = readText(dir + "/best.features");
  EXPECT_NE(features.find("# status: not validated"), std::string::npos) << features;
  EXPECT_NE(features.find("# gp_fitness: "), std::string::npos) << features;
}

TEST(FrontDoor, PlainGpfdIsAUsageError) {
  const auto r = runGpfd("");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("evolve"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("error: no command given"), std::string::npos) << r.output;
}

// A user's mistake is exit 2 with an `error:` line, never exit 1 (bugs) nor a raw system error.
TEST(FrontDoor, MistakesAreExitTwoWithAPlainMessage) {
  std::string features = "# variables: x, dx, th, dth\n";
  for (int i = 1; i <= 10000; ++i) features += "x * " + std::to_string(i) + "\n";
  const auto many = writeText("ten-thousand.features", features);
  const auto tooMany = runGpfd("assess cartpole --features " + many +
                               " --runs 2 --budget 2 --out " + freshDir("ten-thousand"));
  EXPECT_EQ(tooMany.status, 2) << tooMany.output;
  EXPECT_NE(tooMany.output.find("more than the limit"), std::string::npos) << tooMany.output;
  EXPECT_NE(tooMany.output.find(many), std::string::npos) << tooMany.output;

  const auto loop = ::testing::TempDir() + "/loop-a.toml";
  fs::remove(loop);
  fs::remove(::testing::TempDir() + "/loop-b.toml");
  fs::create_symlink(::testing::TempDir() + "/loop-b.toml", loop);
  fs::create_symlink(loop, ::testing::TempDir() + "/loop-b.toml");
  const auto looped = runGpfd("evolve " + loop);
  EXPECT_EQ(looped.status, 2) << looped.output;
  EXPECT_EQ(looped.output.find("filesystem error"), std::string::npos) << looped.output;

  const auto longOut = runGpfd("evolve --out " + std::string(5000, 'a'));
  EXPECT_EQ(longOut.status, 2);
  EXPECT_EQ(longOut.output.find("filesystem error"), std::string::npos);

  const auto emptyOut = runGpfd("evolve --out ''");
  EXPECT_EQ(emptyOut.status, 2) << emptyOut.output;
  EXPECT_NE(emptyOut.output.find("empty"), std::string::npos) << emptyOut.output;
}

// --out into a directory that holds files but no run: refused without --force, for every
// command that writes results.
TEST(FrontDoor, AnOutThatHoldsFilesNeedsForce) {
  const auto dir = freshDir("busy-out");
  fs::create_directories(dir);
  const auto mine = writeText("busy-out/curve.csv", "mine\n");
  const std::vector<std::string> commands{"evolve " + tinyEvolveConfig("busy-out", 3) + " --quiet",
                                          "train cartpole --quiet",
                                          "assess cartpole --raw --runs 2 --budget 2 --quiet"};
  for (const auto& command : commands) {
    const auto refused = runGpfd(command + " --out " + dir);
    EXPECT_EQ(refused.status, 2) << command << "\n" << refused.output;
    EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
    EXPECT_EQ(readText(mine), "mine\n") << command;
  }
  const auto forced = runGpfd("train cartpole --quiet --param updates=2 --force --out " + dir);
  EXPECT_EQ(forced.status, 0) << forced.output;
  EXPECT_TRUE(fs::exists(dir + "/weights.json"));
}

TEST(FrontDoor, TrainWritesUnderResults) {
  const auto work = freshDir("train-default");
  fs::create_directories(work);
  ASSERT_EQ(runGpfd("train cartpole --quiet --param updates=2", work).status, 0);
  EXPECT_TRUE(fs::exists(work + "/results/train-cartpole-1/curve.csv"));
  ASSERT_EQ(runGpfd("train cartpole --quiet --param updates=2", work).status, 0);
  EXPECT_TRUE(fs::exists(work + "/results/train-cartpole-1-2/curve.csv"));
  EXPECT_FALSE(fs::exists(work + "/gpfd-train-cartpole-1"));
}

}  // namespace
}  // namespace gpfd::testing
