// Bad input to `gpfd evolve` and `gpfd assess`: a clear error naming what and where, exit code
// 2, and no results directory left behind.
#include <gtest/gtest.h>

#include "cli_helpers.hpp"

namespace gpfd::testing {
namespace {

// Runs `args` (which write to `dir`) and expects exit 2, `message` in the output, and no `dir`.
void expectRefused(const std::string& args, const std::string& dir, const std::string& message) {
  const auto r = runGpfd(args);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(r.output.rfind("error: ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find(message), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir)) << args;
}

std::string config(const std::string& name, const std::string& extra) {
  return writeText(name + ".toml",
                   "name = \"bad\"\n[env]\nname = \"cartpole\"\n[learner]\n"
                   "params = { updates = 2 }\n[gp]\npopulation = 4\n"
                   "generations = 1\n" +
                       extra);
}

TEST(BadInput, MissingUnreadableOrInvalidConfig) {
  const auto dir = freshDir("bad-out");
  expectRefused("evolve /nonexistent/c.toml --out " + dir, dir, "cannot read");
  expectRefused("evolve " + writeText("syntax.toml", "name = \"x\"\n[gp\n") + " --out " + dir, dir,
                "invalid TOML");
  expectRefused("evolve " + writeText("syntax2.toml", "a = = 1\n") + " --out " + dir, dir,
                "syntax2.toml:1:");
}

TEST(BadInput, UnknownKeyWithSuggestion) {
  const auto dir = freshDir("bad-out");
  expectRefused("evolve " + config("typo", "tournament_sise = 3\n") + " --out " + dir, dir,
                "unknown key 'gp.tournament_sise' (did you mean 'tournament_size'?)");
  expectRefused("evolve " + config("typo2", "") + " --set gp.populaton=9 --out " + dir, dir,
                "did you mean 'population'?");
  expectRefused("evolve " + config("typo3", "[fitnes]\ntrials = 2\n") + " --out " + dir, dir,
                "unknown key 'fitnes' (did you mean 'fitness'?)");
}

TEST(BadInput, TypeAndRangeErrorsNameTheKeyAndLine) {
  const auto dir = freshDir("bad-out");
  const auto path = config("type", "elitism = \"lots\"\n");
  expectRefused("evolve " + path + " --out " + dir, dir, "gp.elitism must be a number");
  expectRefused("evolve " + path + " --out " + dir, dir, path + ":9:");
  expectRefused("evolve " + config("range", "elitism = 1.5\n") + " --out " + dir, dir,
                "gp.elitism must be in [0, 0.99], not 1.5");
  expectRefused("evolve " + config("range2", "") + " --set gp.population=0 --out " + dir, dir,
                "gp.population must be in");
  expectRefused("evolve " + config("envp", "[env.params]\ngravty = 9.81\n") + " --out " + dir, dir,
                "gravty");
  expectRefused("evolve " + config("learnerp", "") + " --set learner.params.updatez=3 --out " + dir,
                dir, "unknown parameter 'updatez' of learner pg");
  expectRefused("evolve " + config("envname", "") + " --env cartpol --out " + dir, dir, "cartpol");
}

TEST(BadInput, FeaturesFileForTheWrongEnvironment) {
  const auto dir = freshDir("bad-assess");
  const auto features =
      writeText("acrobot.features", "# env: acrobot\n# variables: th1, th2, dth1, dth2\nth1\n");
  expectRefused("assess cartpole --features " + features + " --runs 2 --out " + dir, dir,
                "features file is for env 'acrobot', not 'cartpole'");
  const auto vars = writeText("vars.features", "# variables: a, b, c, d\na\n");
  expectRefused("assess cartpole --features " + vars + " --runs 2 --out " + dir, dir,
                "differ from the environment's");
}

TEST(BadInput, ResumeFromAnotherConfigOrVersion) {
  const auto dir = freshDir("bad-resume");
  const auto path = config("resume", "");
  ASSERT_EQ(runGpfd("evolve " + path + " --quiet --out " + dir).status, 0);
  // Another config than the stored one.
  const auto other = runGpfd("evolve " + config("other", "elitism = 0.2\n") + " --resume " + dir);
  EXPECT_EQ(other.status, 2);
  EXPECT_NE(other.output.find("config differs"), std::string::npos) << other.output;
  // A checkpoint written by another version.
  auto text = readText(dir + "/checkpoint.json");
  const auto at = text.find("\"version\": \"");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 12, "9.9-");
  std::ofstream(dir + "/checkpoint.json") << text;
  const auto version = runGpfd("evolve --resume " + dir);
  EXPECT_EQ(version.status, 2);
  EXPECT_NE(version.output.find("written by gpfd 9.9-"), std::string::npos) << version.output;
  // Flags that would change the run.
  EXPECT_EQ(runGpfd("evolve --resume " + dir + " --seed 5").status, 2);
  // An existing run is never overwritten.
  const auto again = runGpfd("evolve " + path + " --out " + dir);
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.output.find("already holds a run"), std::string::npos);
}

TEST(BadInput, UnwritableOutputOrFullDisk) {
  expectRefused("evolve " + config("unwritable", "") + " --out /dev/null/run", "/dev/null/run",
                "cannot create the results directory");
  // A file-size limit makes every write fail as on a full disk (SIGXFSZ ignored, so write()
  // returns EFBIG): the command fails cleanly and leaves no directory.
  const auto dir = freshDir("full-disk");
  const std::string command = "sh -c \"trap '' XFSZ; ulimit -f 1; exec " +
                              std::string(GPFD_BINARY) + " evolve " + config("full", "") +
                              " --quiet --out " + dir + "\" 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 2) << output;
  EXPECT_NE(output.find("cannot write"), std::string::npos) << output;
  EXPECT_FALSE(std::filesystem::exists(dir));
}

TEST(BadInput, ReproduceRefusesUnknownFiguresAndUnwritableOutput) {
  const auto dir = freshDir("reproduce-bad");
  expectRefused("reproduce fig9 --out " + dir, dir, "unknown figure 'fig9'");
  expectRefused("reproduce fig3 --out /dev/null/reproduce", "/dev/null/reproduce",
                "cannot create the output directory");
  EXPECT_EQ(runGpfd("reproduce fig3 --scale huge --out " + dir).status, 2);
  EXPECT_EQ(runGpfd("reproduce fig3 --threads -1 --out " + dir).status, 2);
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace
}  // namespace gpfd::testing
