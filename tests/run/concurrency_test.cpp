// One writer per results directory: a second `gpfd evolve`, `evolve --resume`, `assess` or
// `reproduce` into a directory that another process is writing is refused (exit 2, naming the
// holder's pid), and the directory keeps the first run's files only.
#include <gtest/gtest.h>
#include <signal.h>

#include "cli_helpers.hpp"
#include "gpfd/util/directory_lock.hpp"

namespace gpfd::testing {
namespace {

// The tiny cart-pole config with many generations: still running when the second writer comes.
std::string longConfig(int seed) {
  auto text = readText(tinyEvolveConfig("long-" + std::to_string(seed), seed));
  text.replace(text.find("generations = 6"), 15, "generations = 100000");
  return writeText("long-" + std::to_string(seed) + ".toml", text);
}

void expectRefusedBy(const CommandResult& r, long pid) {
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(r.output.rfind("error: another gpfd process (pid " + std::to_string(pid) + ")", 0), 0u)
      << r.output;
}

TEST(Concurrency, SecondEvolveIntoTheSameDirectoryIsRefused) {
  // The reproduction: seed 1 running, then seed 7 into the same directory.
  const auto dir = freshDir("concurrent-evolve");
  const auto first = startGpfd("evolve " + longConfig(1) + " --quiet --out " + dir,
                               ::testing::TempDir() + "/concurrent-first.log");
  ASSERT_TRUE(waitForFile(dir + "/checkpoint.json"));
  expectRefusedBy(runGpfd("evolve " + longConfig(7) + " --population 12 --out " + dir), first.pid);
  expectRefusedBy(runGpfd("evolve --resume " + dir), first.pid);
  kill(first.pid, SIGINT);  // Stops after a checkpoint.
  EXPECT_EQ(first.wait(), 130) << readText(first.outputFile);

  // Every file is the seed-1 run's.
  EXPECT_NE(readText(dir + "/config.toml").find("seed = 1\n"), std::string::npos);
  EXPECT_NE(readText(dir + "/run.json").find("\"seed\": 1,"), std::string::npos);
  EXPECT_NE(readText(dir + "/best.features").find("# seed: 1\n"), std::string::npos);
  EXPECT_NE(readText(dir + "/checkpoint.json").find("seed = 1\\n"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir + "/" + DirectoryLock::kFileName));
  // Once the first has ended, the directory can be resumed (and is not overwritten); resuming a
  // finished run says so.
  const auto resumed = runGpfd("evolve --quiet --resume " + dir + " --generations 1");
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  const auto again = runGpfd("evolve --resume " + dir + " --generations 1");
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(again.output, "the run in " + dir +
                              " is already complete (generations: 1); pass --generations N (more "
                              "than 1) to extend it\n");
}

TEST(Concurrency, AssessAndReproduceRefuseALockedDirectory) {
  // This test process holds the lock; gpfd runs as a second process.
  const auto dir = freshDir("concurrent-locked");
  const DirectoryLock lock(dir);
  const auto features = writeText("concurrent.features", "# env: cartpole\nx + th\n");
  expectRefusedBy(
      runGpfd("assess cartpole --features " + features + " --runs 2 --budget 2 --out " + dir),
      ::getpid());
  expectRefusedBy(runGpfd("reproduce fig3 --out " + dir), ::getpid());
  expectRefusedBy(runGpfd("evolve-toy --generations 1 --out " + dir), ::getpid());
  // Nothing was written next to the lock file.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1u);
}

}  // namespace
}  // namespace gpfd::testing
