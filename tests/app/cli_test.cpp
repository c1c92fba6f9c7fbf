// The gpfd command line as a user meets it: help, version, and bad input.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace {

struct Result {
  int status;
  std::string output;
};

Result run(const std::string& args) {
  Result r{0, {}};
  FILE* pipe = popen((std::string(GPFD_BINARY) + " " + args + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(Cli, HelpAndVersion) {
  const auto help = run("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("evolve-toy"), std::string::npos);
  EXPECT_NE(help.output.find("features"), std::string::npos);
  const auto version = run("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output.rfind("gpfd ", 0), 0u);
  EXPECT_NE(version.output.find('('), std::string::npos);  // The git revision.
}

TEST(Cli, UnknownCommandOrFlagExitsTwo) {
  EXPECT_EQ(run("frobnicate").status, 2);
  EXPECT_EQ(run("evolve-toy --no-such-flag").status, 2);
  EXPECT_EQ(run("evolve-toy --population -3").status, 2);
}

TEST(Cli, FeaturesShowPrintsBothFormats) {
  const auto path =
      writeTemp("ok.features", "# variables: a, b\n# env: demo\nsin(a) * (b - 1)\nmax(a, 2)\n");
  const auto infix = run("features show " + path);
  EXPECT_EQ(infix.status, 0);
  EXPECT_EQ(infix.output, "sin(a) * (b - 1)\nmax(a, 2)\n");
  const auto sexpr = run("features show --format sexpr " + path);
  EXPECT_EQ(sexpr.output, "(* (sin a) (- b 1))\n(max a 2)\n");
}

TEST(Cli, MalformedFeaturesFileGivesLineColumnAndExitTwo) {
  const auto path = writeTemp("bad.features", "# variables: a, b\nsin(a)\na + cos(b, a)\n");
  const auto r = run("features show " + path);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "error: wrong arity: 'cos' takes 1 argument, got 2 (" + path + ":3:5)\n");
  const auto missing = run("features show /nonexistent/x.features");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("error: cannot read"), std::string::npos);
}

}  // namespace
