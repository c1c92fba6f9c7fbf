// Every command with --help, and with bad flags: exit code 2 and one line
// `error: <what> (<where>)`, with the bound or the suggestion that helps.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "../run/cli_helpers.hpp"
#include "gpfd/jit/x86_compiler.hpp"

namespace {

using gpfd::testing::runGpfd;
using gpfd::testing::writeText;

const std::vector<std::string> kCommands{
    "evolve",   "evolve-toy",    "assess",          "reproduce",     "train",     "envs",
    "simulate", "features show", "features export", "features eval", "bench jit", "fitness-noise"};

TEST(CliTable, EveryCommandHasHelp) {
  for (const auto& command : kCommands) {
    const auto r = runGpfd(command + " --help");
    EXPECT_EQ(r.status, 0) << command;
    EXPECT_NE(r.output.find("Usage:"), std::string::npos) << command << "\n" << r.output;
  }
  // Plain `gpfd` lists the commands (and is a usage error: nothing ran).
  const auto plain = runGpfd("");
  EXPECT_EQ(plain.status, 2);
  for (const char* command : {"evolve", "assess", "reproduce", "simulate", "features", "bench"}) {
    EXPECT_NE(plain.output.find(command), std::string::npos) << command;
  }
}

TEST(CliTable, HelpShowsTheBounds) {
  const std::vector<std::pair<std::string, std::string>> bounds{
      {"evolve", "in [2, 1000000]"},       {"evolve", "in [0, 4096]"},
      {"evolve-toy", "in [2, 1000000]"},   {"evolve-toy", "in [10, 1000000]"},
      {"assess", "in [1, 100000]"},        {"assess", "in [1, 1000000]"},
      {"simulate", "in [0, 10000000]"},    {"train", "in [0, 100000]"},
      {"bench jit", "in [1, 1000000000]"}, {"fitness-noise", "in [2, 10000]"},
      {"reproduce", "in [1, 100]"},        {"reproduce", "in [0, 4096]"}};
  for (const auto& [command, bound] : bounds) {
    EXPECT_NE(runGpfd(command + " --help").output.find(bound), std::string::npos)
        << command << ": " << bound;
  }
}

struct Bad {
  std::string args;
  std::string message;  // Expected in the output: the what and/or the where.
};

TEST(CliTable, BadInputIsOneErrorLineWithExitTwo) {
  const auto features =
      writeText("table.features", "# env: cartpole\n# variables: x, dx, th, dth\nx + th\n");
  const std::string dir = ::testing::TempDir();
  const std::vector<Bad> table{
      // Commands and flags, with did-you-mean.
      {"evolv", "unknown command 'evolv' (did you mean 'evolve'?) (gpfd)"},
      {"frobnicate", "unknown command 'frobnicate' (commands: "},
      {"--bogus", "unknown flag '--bogus' (gpfd)"},
      {"evolve --popultion 5",
       "unknown flag '--popultion' (did you mean '--population'?) (gpfd evolve)"},
      {"evolve a.toml b", "unexpected argument 'b' (gpfd evolve)"},
      {"features", "missing command: one of show, export, eval (gpfd features)"},
      {"features shw x", "unknown command 'shw' (did you mean 'show'?) (gpfd features)"},
      {"bench", "missing command: one of jit (gpfd bench)"},
      {"simulate", "missing ENV (gpfd simulate)"},
      {"features show", "missing FILE (gpfd features show)"},
      {"evolve --population", "a value is missing (gpfd evolve --population)"},
      // Ranges print their real bounds.
      {"evolve --population 1", "1 is outside [2, 1000000] (gpfd evolve --population)"},
      {"evolve --population 5000000", "5000000 is outside [2, 1000000] (gpfd evolve --population)"},
      {"evolve --population abc", "'abc' is not an integer (gpfd evolve --population)"},
      {"evolve --generations 0", "0 is outside [1, 1000000] (gpfd evolve --generations)"},
      {"evolve --threads 5000", "5000 is outside [0, 4096] (gpfd evolve --threads)"},
      {"evolve --seed -1",
       "'-1' is not a seed (an integer in [0, 18446744073709551615]) (gpfd evolve --seed)"},
      {"evolve-toy --population 0", "0 is outside [2, 1000000] (gpfd evolve-toy --population)"},
      {"evolve-toy --population 100000000", "100000000 is outside [2, 1000000]"},
      {"evolve-toy --samples 5", "5 is outside [10, 1000000] (gpfd evolve-toy --samples)"},
      {"assess cartpole --raw --runs 0", "0 is outside [1, 100000] (gpfd assess --runs)"},
      {"assess cartpole --raw --budget 0", "0 is outside [1, 1000000] (gpfd assess --budget)"},
      {"assess cartpole --raw --fourier 10", "10 is outside [1, 9] (gpfd assess --fourier)"},
      // Bounded together: the memory that every run's learning curve would take.
      {"assess cartpole --raw --runs 100000 --budget 1000000",
       "the learning curves of every run would need about"},
      {"evolve --population 1000000 --set genome.max_features=1000 --set genome.max_size=65536",
       "the population at its genome size limits would need about"},
      {"reproduce --scale huge", "'huge' is not one of quick, paper (gpfd reproduce --scale)"},
      {"reproduce --scale papr", "(did you mean 'paper'?) (gpfd reproduce --scale)"},
      {"reproduce --threads -1", "-1 is outside [0, 4096] (gpfd reproduce --threads)"},
      {"reproduce fig9 --out " + dir + "/fig9", "unknown figure 'fig9'"},
      {"reproduce --gp-runs 0", "0 is outside [1, 100] (gpfd reproduce --gp-runs)"},
      {"evolve --runs 1001", "1001 is outside [1, 1000] (gpfd evolve --runs)"},
      {"fitness-noise", "missing RUN (gpfd fitness-noise)"},
      {"fitness-noise " + dir + " --pairs 0",
       "0 is outside [1, 1000] (gpfd fitness-noise --pairs)"},
      {"train cartpole --learner xx", "unknown learner 'xx' (known: ars, lpi, pg) (--learner)"},
      {"train cartpole --eval -1", "-1 is outside [0, 100000] (gpfd train --eval)"},
      {"simulate cartpole --steps -3", "-3 is outside [0, 10000000] (gpfd simulate --steps)"},
      {"simulate cartpole --policy greedy --steps 3", "'greedy' is not one of random"},
      {"simulate cartpole --steps 3", "without a policy or --actions only the initial state"},
      {"features show --format xml " + features, "'xml' is not one of infix, sexpr"},
      {"features show " + dir,
       "a directory without best.features: give a features file or a "
       "run's results directory (" +
           dir + ")"},
      {"assess cartpole --features " + dir, "a directory, not a file (" + dir + ")"},
      {"features eval " + features, "give either --state v1,v2,... or --states FILE"},
      {"features eval " + features + " --state 1,2", "2 values for the 4 variables"},
      {"bench jit --calls 0", "0 is outside [1, 1000000000] (gpfd bench jit --calls)"},
      {"bench jit --calls -3", "-3 is outside [1, 1000000000] (gpfd bench jit --calls)"},
      {"bench jit --runs 0", "0 is outside [1, 1000] (gpfd bench jit --runs)"},
      {"bench jit --depths 9-2", "depths must be a range within 1-16"},
      {"envs --bogus", "unknown flag '--bogus' (gpfd envs)"},
      // Environment names, shipped config names and --set keys.
      {"simulate cartpol", "unknown environment 'cartpol' (did you mean 'cartpole'?)"},
      {"train cartpol",
       "(did you mean 'cartpole'?) (known: Acrobot-v1, CartPole-v1, MountainCar-v0, "
       "MountainCarContinuous-v0, Pendulum-v1, acrobot, cartpole, swimmer, tetris) "
       "(gpfd train)"},
      {"assess cartpol --raw", "unknown environment 'cartpol' (did you mean 'cartpole'?)"},
      {"evolve --env acrobt", "unknown environment 'acrobt' (did you mean 'acrobot'?)"},
      {"evolve acrobot-quik",
       "neither a file nor a shipped config (did you mean "
       "'acrobot-quick'?) (acrobot-quik)"},
      {"evolve --set gp.population=1",
       "gp.population must be in [2, 1000000], not 1 "
       "(--set gp.population)"},
  };
  const std::regex format(R"(error: [^\n]+ \([^\n]+\)\n)");
  for (const auto& bad : table) {
    // A build without the JIT refuses `bench jit` before reading its arguments.
    if (!gpfd::jit::jitAvailable() && bad.args.starts_with("bench jit")) continue;
    const auto r = runGpfd(bad.args);
    EXPECT_EQ(r.status, 2) << bad.args << "\n" << r.output;
    EXPECT_TRUE(std::regex_match(r.output, format)) << bad.args << "\n" << r.output;
    EXPECT_NE(r.output.find(bad.message), std::string::npos) << bad.args << "\n" << r.output;
  }
}

}  // namespace
