// Ctrl-C (SIGINT to the terminal's process group) ends `evolve` and `reproduce` with exit code
// 130 after the step that was running, and a rerun continues.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <string>

#include "cli_helpers.hpp"
#include "gpfd/jit/x86_compiler.hpp"

namespace gpfd::testing {
namespace {

// Starts `args` in its own process group, waits for `file`, sends SIGINT to the whole group as a
// terminal's Ctrl-C does, and returns the exit code.
int interruptWhenExists(const std::string& args, const std::string& file, std::string& output) {
  // One log per call and per test process: ctest runs the tests of this file in parallel.
  static int calls = 0;
  const std::string log = ::testing::TempDir() + "/interrupt-" + std::to_string(getpid()) + "-" +
                          std::to_string(++calls) + ".log";
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    execl("/bin/sh", "sh", "-c",
          ("exec " + std::string(GPFD_BINARY) + " " + args + " > '" + log + "' 2>&1").c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);  // Either side may run first.
  EXPECT_TRUE(waitForFile(file, 120)) << file;
  kill(-pid, SIGINT);
  const int code = Background{pid, log}.wait();
  output = readText(log);
  return code;
}

TEST(Interrupt, EvolveExitsWith130AndResumes) {
  auto text = readText(tinyEvolveConfig("interrupted-evolve", 2));
  text.replace(text.find("generations = 6"), 15, "generations = 100000");
  const auto config = writeText("interrupted-evolve.toml", text);
  const auto dir = freshDir("interrupted-evolve");
  std::string output;
  EXPECT_EQ(
      interruptWhenExists("evolve " + config + " --out " + dir, dir + "/checkpoint.json", output),
      130);
  EXPECT_NE(output.find("Continue with: gpfd evolve --resume " + dir), std::string::npos) << output;
}

TEST(Interrupt, ReproduceExitsWith130DuringAGpRunAndDuringTheBenchmark) {
  const auto dir = freshDir("interrupted-reproduce");
  std::string output;
  EXPECT_EQ(interruptWhenExists("reproduce fig1 --scale quick --out " + dir,
                                dir + "/fig1/evolve-cartpole-quick/checkpoint.json", output),
            130);
  EXPECT_NE(output.find("interrupted; run the same command again to continue"), std::string::npos)
      << output;
  EXPECT_EQ(output.find("error:"), std::string::npos) << output;
  // fig3's JIT benchmark (in-process) finishes its measurement, then the run stops. A build
  // without the JIT has no Figure 3.
  if (!gpfd::jit::jitAvailable()) return;
  EXPECT_EQ(
      interruptWhenExists("reproduce fig3 --scale quick --out " + dir, dir + "/fig3/jit", output),
      130);
  EXPECT_NE(output.find("interrupted"), std::string::npos) << output;
}

}  // namespace
}  // namespace gpfd::testing
