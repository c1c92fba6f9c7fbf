// `gpfd reproduce` end to end on its cheapest experiment (fig3, the JIT benchmark, quick scale):
// the figure's data, the report in both forms, and a rerun that reuses the finished step.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_helpers.hpp"
#include "gpfd/jit/x86_compiler.hpp"

namespace gpfd::testing {
namespace {

TEST(Reproduce, Figure3WritesItsDataAndTheReportAndARerunReusesIt) {
  if (!jit::jitAvailable()) GTEST_SKIP() << "needs native code: this build has no JIT";
  const auto dir = freshDir("reproduce-fig3");
  const auto first = runGpfd("reproduce fig3 --scale quick --quiet --out " + dir);
  ASSERT_EQ(first.status, 0) << first.output;
  for (const char* file : {"/fig3/jit/jit.csv", "/fig3/jit/jit_unary.csv", "/fig3/jit/jit.png",
                           "/fig3/jit/jit.svg", "/fig3/section.json", "/report.html"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + file)) << file;
  }
  const std::string report = readText(dir + "/report.md");
  EXPECT_NE(report.find("Figure 3: speed-up of compiled feature functions"), std::string::npos);
  EXPECT_NE(report.find("fig3/jit/jit.png"), std::string::npos);
  EXPECT_NE(readText(dir + "/report.html").find("data:image/png;base64,"), std::string::npos);

  // The benchmark is not run again: its data stay byte for byte.
  const std::string csv = readText(dir + "/fig3/jit/jit.csv");
  const auto second = runGpfd("reproduce fig3 --scale quick --quiet --out " + dir);
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(readText(dir + "/fig3/jit/jit.csv"), csv);
}

}  // namespace
}  // namespace gpfd::testing
