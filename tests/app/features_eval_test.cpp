// `gpfd features eval`: the values it prints are the JIT's (CompiledFeatureMap), bit for bit.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "../jit/random_genomes.hpp"
#include "../run/cli_helpers.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"

namespace gpfd::testing {
namespace {

using jit::testing::randomGenome;
using jit::testing::sameBits;

std::vector<std::vector<double>> parseCsv(const std::string& text, std::string& header) {
  std::istringstream in(text);
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) {
      row.push_back(std::strtod(field.c_str(), nullptr));
    }
    rows.push_back(row);
  }
  return rows;
}

TEST(FeaturesEval, PrintsTheJitsValuesBitForBit) {
  const expr::VariableNames names{"a", "b", "c"};
  Rng rng(11);
  for (int g = 0; g < 20; ++g) {
    expr::FeaturesFile file;
    file.variables = names;
    file.genome = randomGenome(rng, jit::testing::operatorSet("all"), 5, 5, 3);
    const auto path = writeText("eval.features", expr::formatFeaturesFile(file));
    // The genome as the command reads it (printing may fold a constant's sign, say).
    const auto read = expr::readFeaturesFile(path);
    const jit::CompiledFeatureMap map(read.genome, names.size());

    std::string csv = "c,a,b,ignored\n";  // Columns by name, in any order.
    std::vector<std::vector<double>> states;
    for (int s = 0; s < 25; ++s) {
      std::vector<double> state(3);
      for (double& x : state) {
        do {
          x = jit::testing::randomState(rng, 1)[0];
        } while (!std::isfinite(x));
      }
      states.push_back(state);
      csv += fmt::format("{},{},{},\n", state[2], state[0], state[1]);
    }
    const auto statesPath = writeText("eval-states.csv", csv);
    const auto r = runGpfd("features eval " + path + " --states " + statesPath);
    ASSERT_EQ(r.status, 0) << r.output;
    std::string header;
    const auto rows = parseCsv(r.output, header);
    std::string expectedHeader = "f1";
    for (std::size_t k = 2; k <= map.outputDim(); ++k) expectedHeader += ",f" + std::to_string(k);
    EXPECT_EQ(header, expectedHeader);
    ASSERT_EQ(rows.size(), states.size());
    std::vector<double> want(map.outputDim());
    for (std::size_t s = 0; s < states.size(); ++s) {
      map.evaluate(states[s].data(), want.data());
      ASSERT_EQ(rows[s].size(), want.size());
      for (std::size_t k = 0; k < want.size(); ++k) {
        EXPECT_TRUE(sameBits(rows[s][k], want[k]))
            << "genome " << g << " state " << s << " feature " << k << ": " << rows[s][k] << " vs "
            << want[k];
      }
    }
    // One state on the command line gives the same first row.
    const auto one = runGpfd(fmt::format("features eval {} --state {},{},{}", path, states[0][0],
                                         states[0][1], states[0][2]));
    ASSERT_EQ(one.status, 0) << one.output;
    EXPECT_EQ(one.output, r.output.substr(0, r.output.find('\n', header.size() + 1) + 1));
  }
}

TEST(FeaturesEval, ReadsATrajectoryOfGpfdSimulate) {
  const auto trajectory = runGpfd("simulate cartpole --policy random --steps 4 --seed 2");
  ASSERT_EQ(trajectory.status, 0);
  const auto states = writeText("trajectory.csv", trajectory.output);
  const auto features =
      writeText("cartpole.features", "# env: cartpole\n# variables: x, dx, th, dth\nth\nx * 2\n");
  const auto r = runGpfd("features eval " + features + " --states " + states);
  ASSERT_EQ(r.status, 0) << r.output;
  std::string header;
  const auto rows = parseCsv(r.output, header);
  std::string simulateHeader;
  const auto simulated = parseCsv(trajectory.output, simulateHeader);
  EXPECT_EQ(header, "f1,f2");
  ASSERT_EQ(rows.size(), 5u);  // The initial state and four steps.
  for (std::size_t s = 0; s < rows.size(); ++s) {
    EXPECT_EQ(rows[s][0], simulated[s][4]) << s;  // step,force,x,dx,th: th is column 4.
    EXPECT_EQ(rows[s][1], simulated[s][2] * 2) << s;
  }
}

}  // namespace
}  // namespace gpfd::testing
