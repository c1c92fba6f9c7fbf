// The rest of a new user's trial (issue 13): what each command says when something is off.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "../run/cli_helpers.hpp"
#include "gpfd/jit/x86_compiler.hpp"

namespace gpfd::testing {
namespace {

std::size_t countLines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(NewUser, AssessNeverOverwritesAnEarlierAssessment) {
  const auto work = freshDir("assess-folders");
  std::filesystem::create_directories(work);
  const std::string args = "assess cartpole --raw --budget 2 --quiet --runs ";
  ASSERT_EQ(runGpfd(args + "3", work).status, 0);
  const auto first = readText(work + "/results/assess-cartpole/summary.csv");
  ASSERT_NE(first.find("original,3,"), std::string::npos) << first;
  // The same command again: a fresh folder, the first assessment untouched.
  const auto again = runGpfd(args + "2", work);
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(readText(work + "/results/assess-cartpole/summary.csv"), first);
  EXPECT_NE(readText(work + "/results/assess-cartpole-2/summary.csv").find("original,2,"),
            std::string::npos);
  // An explicit --out that holds an assessment needs --force.
  const auto refused = runGpfd(args + "2 --out results/assess-cartpole", work);
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.output.find("already holds an assessment; pass --force"), std::string::npos)
      << refused.output;
  EXPECT_EQ(readText(work + "/results/assess-cartpole/summary.csv"), first);
  ASSERT_EQ(runGpfd(args + "2 --out results/assess-cartpole --force", work).status, 0);
  EXPECT_NE(readText(work + "/results/assess-cartpole/summary.csv").find("original,2,"),
            std::string::npos);
}

TEST(NewUser, A200000TermFeatureIsRefusedWhereTheLimitIsCrossed) {
  std::string chain = "x";
  for (int i = 1; i < 200000; ++i) chain += "+x";
  const auto path = writeText("chain.features", "# variables: x\n" + chain + "\n");
  const auto r = runGpfd("features show " + path);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "error: too deep: depth exceeds the limit of 64 (" + path + ":2:128)\n");
}

TEST(NewUser, FeaturesFilesWithAByteOrderMarkAreRead) {
  const auto path = writeText("bom.features", "\xEF\xBB\xBF# variables: a, b\nsin(a) + b\n");
  const auto r = runGpfd("features show " + path);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "sin(a) + b\n");
}

TEST(NewUser, ATruncatedCheckpointGetsAShortMessage) {
  const auto dir = freshDir("truncated-checkpoint");
  ASSERT_EQ(runGpfd("evolve " + tinyEvolveConfig("truncated", 1) + " --quiet --out " + dir).status,
            0);
  const auto text = readText(dir + "/checkpoint.json");
  const auto config = text.find("\"config\": \"");
  ASSERT_NE(config, std::string::npos);
  std::ofstream(dir + "/checkpoint.json") << text.substr(0, config + 200);  // Inside the config.
  const auto r = runGpfd("evolve --resume " + dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output.rfind("error: corrupt checkpoint: ", 0), 0u) << r.output;
  EXPECT_EQ(countLines(r.output), 1u) << r.output;
  EXPECT_LT(r.output.size(), 300u) << r.output;
}

TEST(NewUser, MoreThreadsThanCoresAreClampedWithANote) {
  const unsigned cores = std::thread::hardware_concurrency();
  if (cores == 0 || cores >= 64) GTEST_SKIP() << "needs fewer than 64 cores";
  const auto dir = freshDir("toy-threads");
  const auto r =
      runGpfd("evolve-toy --threads 64 --generations 1 --population 10 --quiet --out " + dir);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("TBB Warning"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("note: --threads 64 is more than the " + std::to_string(cores) +
                          " cores available; using " + std::to_string(cores)),
            std::string::npos)
      << r.output;
}

TEST(NewUser, BenchJitSummarisesAnyDepthRange) {
  if (!gpfd::jit::jitAvailable()) GTEST_SKIP() << "needs native code: the JIT benchmark";
  const auto dir = freshDir("bench-depths");
  const auto r =
      runGpfd("bench jit --depths 2-4 --calls 2000 --runs 1 --memory-cycles 0 --out " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("compile time, 3 nodes (depth 2): "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" us; 15 nodes (depth 4): "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(":  us"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("ratio \n"), std::string::npos) << r.output;
}

// cmake/write_version.cmake on a scratch repository: the revision, "-dirty" once a tracked file
// changes or a new file appears.
TEST(NewUser, VersionMarksAModifiedTree) {
  const auto repo = freshDir("version-repo");
  std::filesystem::create_directories(repo);
  const std::string git = "cd '" + repo + "' && git -c user.name=t -c user.email=t@t ";
  ASSERT_EQ(
      std::system(
          (git + "init -q && echo a > a && " + git + "add a && " + git + "commit -qm a").c_str()),
      0);
  const auto revision = [&] {
    const std::string header = repo + ".hpp";
    const std::string command = "cmake -DSOURCE_DIR='" + repo + "' -DOUTPUT='" + header +
                                "' -DVERSION=1 -P '" GPFD_SOURCE_DIR "/cmake/write_version.cmake'";
    EXPECT_EQ(std::system(command.c_str()), 0);
    const auto text = readText(header);
    const auto at = text.find("kRevision = \"") + 13;
    return text.substr(at, text.find('"', at) - at);
  };
  EXPECT_EQ(revision().find("dirty"), std::string::npos);
  std::ofstream(repo + "/new") << "untracked";
  EXPECT_NE(revision().find("-dirty"), std::string::npos);
  std::filesystem::remove(repo + "/new");
  std::ofstream(repo + "/a") << "changed";
  EXPECT_NE(revision().find("-dirty"), std::string::npos);
}

}  // namespace
}  // namespace gpfd::testing
