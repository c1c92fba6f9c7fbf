// `gpfd simulate` and `gpfd envs` end to end: CSV layout, replay bit for bit, and bad input.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "gpfd/env/simulate.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

struct ProcessResult {
  int code = -1;
  std::string out;
};

// Runs the gpfd binary with `args` (stderr discarded) and returns its exit code and stdout.
ProcessResult gpfd(const std::string& args) {
  ProcessResult run;
  const std::string command = std::string(GPFD_BINARY) + " " + args + " 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    run.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) out.push_back(line);
  return out;
}

std::string field(const std::string& line, std::size_t index) {
  std::stringstream ss(line);
  std::string f;
  for (std::size_t i = 0; i <= index; ++i) std::getline(ss, f, ',');
  return f;
}

TEST(Simulate, WritesHeaderInitialRowAndOneRowPerStep) {
  const ProcessResult run = gpfd("simulate acrobot --policy random --steps 5 --seed 7");
  ASSERT_EQ(run.code, 0);
  const auto rows = lines(run.out);
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(rows[0], "step,torque,th1,th2,dth1,dth2,reward,terminated,truncated");
  EXPECT_EQ(rows[1].substr(0, 3), "0,,");
  EXPECT_EQ(field(rows[6], 0), "5");
  EXPECT_EQ(field(rows[6], 6), "-1");
}

TEST(Simulate, ReplayingTheActionsFromTheInitialStateGivesTheSameCsv) {
  for (const std::string env :
       {"acrobot", "cartpole --param integrator=rk4", "swimmer --param segments=5", "tetris"}) {
    const ProcessResult first = gpfd("simulate " + env + " --policy random --steps 40 --seed 3");
    ASSERT_EQ(first.code, 0) << env;
    const auto rows = lines(first.out);
    const auto header = rows[0];
    std::size_t actionCount = 0;
    // The action columns are the empty fields after the step in row 0.
    const ProcessResult names = gpfd("simulate " + env + " --steps 0 --policy random");
    ASSERT_EQ(names.code, 0);
    const std::string row0 = lines(names.out)[1];
    for (std::size_t i = 1; field(row0, i).empty(); ++i) ++actionCount;
    std::string state, actions;
    for (std::size_t i = 1 + actionCount; field(header, i) != "reward"; ++i) {
      // Not ("" or ",") + field(...): GCC 12 -O3 reports a false -Wrestrict on that.
      if (!state.empty()) state += ',';
      state += field(rows[1], i);
    }
    for (std::size_t r = 2; r < rows.size(); ++r) {
      for (std::size_t i = 1; i <= actionCount; ++i) {
        actions += field(rows[r], i) + (i == actionCount ? "\n" : ",");
      }
    }
    const std::string file = ::testing::TempDir() + "gpfd_actions.csv";
    std::ofstream(file) << actions;
    const ProcessResult replay =
        gpfd("simulate " + env + " --seed 3 --state " + state + " --actions " + file);
    ASSERT_EQ(replay.code, 0) << env;
    EXPECT_EQ(replay.out, first.out) << env;
  }
}

TEST(Simulate, StopsAtTerminationUnlessToldNotTo) {
  // Cart-pole tipped beyond 12 degrees fails on the first step.
  const std::string base = "simulate cartpole --state 0,0,0.3,0 --policy random --steps 5";
  EXPECT_EQ(lines(gpfd(base).out).size(), 3u);
  EXPECT_EQ(lines(gpfd(base + " --no-stop").out).size(), 7u);
}

TEST(Simulate, ClipsContinuousActions) {
  const std::string file = ::testing::TempDir() + "gpfd_big_action.csv";
  std::ofstream(file) << "25\n-1e9\n";
  const ProcessResult run = gpfd("simulate cartpole --actions " + file);
  ASSERT_EQ(run.code, 0);
  const auto rows = lines(run.out);
  EXPECT_EQ(field(rows[2], 1), "10");
  EXPECT_EQ(field(rows[3], 1), "-10");
}

TEST(Simulate, BadInputExitsWithTwoAndWritesNoCsv) {
  const std::string file = ::testing::TempDir() + "gpfd_bad_actions.csv";
  for (const std::string content : {"0.5\n1,2\n", "0.5\nabc\n", "0.5\nnan\n", "0.5\n\n,\n"}) {
    std::ofstream(file) << content;
    const ProcessResult run = gpfd("simulate acrobot --actions " + file);
    EXPECT_EQ(run.code, 2) << content;
    EXPECT_TRUE(run.out.empty()) << content;
  }
  for (const std::string& args : std::vector<std::string>{
           "simulate pendulum --policy random --steps 3", "simulate acrobot --param nope=1",
           "simulate acrobot --param dt=fast", "simulate acrobot --state 1,2,3",
           "simulate acrobot --state 1,2,x,4", "simulate tetris --state 1,2",
           "simulate acrobot --param actions=discrete --actions " + file}) {
    const ProcessResult run = gpfd(args);
    EXPECT_EQ(run.code, 2) << args;
    EXPECT_TRUE(run.out.empty()) << args;
  }
  std::ofstream(file) << "0,9\n";  // Tetris: no piece fits at column 9 of 8.
  EXPECT_EQ(gpfd("simulate tetris --actions " + file).code, 2);
}

TEST(Simulate, EnvsListsEveryEnvironment) {
  const ProcessResult run = gpfd("envs");
  ASSERT_EQ(run.code, 0);
  for (const char* word :
       {"acrobot:", "cartpole:", "swimmer:", "tetris:", "segments = 3", "viscosity = 10",
        "max_torque = 5", "dynamics = book", "dt = 0.2", "state = paper", "dGx, dGy, th1"}) {
    EXPECT_NE(run.out.find(word), std::string::npos) << word;
  }
}

TEST(Simulate, ParsesNumberLists) {
  EXPECT_EQ(parseNumberList("1,-2.5, 3e2", "x"), (std::vector<double>{1, -2.5, 300}));
  EXPECT_THROW(parseNumberList("1,,2", "x"), InputError);
  EXPECT_THROW(parseNumberList("inf", "x"), InputError);
  EXPECT_THROW(parseNumberList("1.5.2", "x"), InputError);
}

}  // namespace
}  // namespace gpfd::env
