#include "gpfd/experiments/toy_task.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "gpfd/expr/parse.hpp"
#include "gpfd/run/thread_evaluator.hpp"

namespace gpfd::experiments {
namespace {
using namespace gpfd::run;

TEST(ToyTask, PerfectFeaturesGiveRSquaredOne) {
  const ToyTask task(200, 1);
  const auto& names = ToyTask::variableNames();
  expr::Genome perfect;
  perfect.addFeature(expr::parseInfix("x0 * x1", names));
  perfect.addFeature(expr::parseInfix("sin(x2)", names));
  EXPECT_GT(task.rSquared(perfect), 1 - 1e-12);
  expr::Genome partial;
  partial.addFeature(expr::parseInfix("x0 * x1", names));
  EXPECT_LT(task.rSquared(partial), 0.99);
}

// The same seed gives bit-identical statistics with 1 and 2 threads.
TEST(ToyTask, OneAndTwoThreadsAgree) {
  const ToyTask task(100, 5);
  auto config = toyGpConfig(5);
  config.population = 60;
  config.generations = 6;
  std::vector<std::vector<double>> bests;
  for (int threads : {1, 2}) {
    ThreadEvaluator evaluator([&](const expr::Genome& g, Rng&) { return task.rSquared(g); },
                              threads);
    gp::Evolution evolution(config, toySearchSpace(), evaluator);
    std::vector<double> trace;
    evolution.run([&](const gp::GenerationStats& s) {
      trace.push_back(s.best);
      trace.push_back(s.mean);
      trace.push_back(s.meanSize);
      return true;
    });
    bests.push_back(trace);
  }
  EXPECT_EQ(bests[0], bests[1]);
}

std::string runCommand(const std::string& command, int& status) {
  std::string output;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  status = pclose(pipe);
  return output;
}

// The command a new user runs: R^2 > 0.999 with the default budget and a fixed seed, `R2 <value>`
// as the last line, and the features written to DIR/best.features.
TEST(ToyTask, EvolveToyCommandFindsTheFeatures) {
  const std::string dir = ::testing::TempDir() + "/toy";
  int status = 0;
  const auto output =
      runCommand(std::string(GPFD_BINARY) + " evolve-toy --seed 1 --quiet --out " + dir, status);
  ASSERT_EQ(status, 0) << output;
  const auto lastLine = output.substr(output.rfind("R2 "));
  EXPECT_GT(std::stod(lastLine.substr(3)), 0.999) << output;
  std::ifstream file(dir + "/best.features");
  ASSERT_TRUE(file.good());
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_NE(text.str().find("# variables: x0, x1, x2"), std::string::npos);
}

}  // namespace
}  // namespace gpfd::experiments
