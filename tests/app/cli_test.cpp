// The gpfd command line as a user meets it: help, version, and bad input.
#include <gtest/gtest.h>

#include <string>

#include "../run/cli_helpers.hpp"

namespace {

using gpfd::testing::runGpfd;
using gpfd::testing::writeText;

TEST(Cli, HelpAndVersion) {
  const auto help = runGpfd("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("evolve-toy"), std::string::npos);
  EXPECT_NE(help.output.find("features"), std::string::npos);
  const auto version = runGpfd("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output.rfind("gpfd ", 0), 0u);
  EXPECT_NE(version.output.find('('), std::string::npos);  // The git revision.
}

TEST(Cli, UnknownCommandOrFlagExitsTwo) {
  EXPECT_EQ(runGpfd("frobnicate").status, 2);
  EXPECT_EQ(runGpfd("evolve-toy --no-such-flag").status, 2);
  EXPECT_EQ(runGpfd("evolve-toy --population -3").status, 2);
}

TEST(Cli, FeaturesShowPrintsBothFormats) {
  const auto path =
      writeText("ok.features", "# variables: a, b\n# env: demo\nsin(a) * (b - 1)\nmax(a, 2)\n");
  const auto infix = runGpfd("features show " + path);
  EXPECT_EQ(infix.status, 0);
  EXPECT_EQ(infix.output, "sin(a) * (b - 1)\nmax(a, 2)\n");
  const auto sexpr = runGpfd("features show --format sexpr " + path);
  EXPECT_EQ(sexpr.output, "(* (sin a) (- b 1))\n(max a 2)\n");
}

TEST(Cli, MalformedFeaturesFileGivesLineColumnAndExitTwo) {
  const auto path = writeText("bad.features", "# variables: a, b\nsin(a)\na + cos(b, a)\n");
  const auto r = runGpfd("features show " + path);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.output, "error: wrong arity: 'cos' takes 1 argument, got 2 (" + path + ":3:5)\n");
  const auto missing = runGpfd("features show /nonexistent/x.features");
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(missing.output.find("error: cannot read"), std::string::npos);
}

}  // namespace
