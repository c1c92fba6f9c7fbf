// Acrobot and cart-pole against golden trajectories computed independently from the equations of
// docs/benchmarks.md by tests/data/env/make_golden.py (plain Python, see its docstring).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"

namespace gpfd::env {
namespace {

struct Row {
  int step = 0;
  std::string action;
  std::vector<double> state;
  std::string reward;
  std::string terminated;
};

std::map<std::string, std::vector<Row>> readCases(const std::string& file) {
  std::ifstream in(std::string(GPFD_TEST_DATA_DIR) + "/env/" + file);
  EXPECT_TRUE(in) << file;
  std::map<std::string, std::vector<Row>> cases;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string field;
    while (std::getline(ss, field, ',')) f.push_back(field);
    if (line.back() == ',') f.emplace_back();
    EXPECT_EQ(f.size(), 9u) << line;
    Row row;
    row.step = std::stoi(f[1]);
    row.action = f[2];
    for (int i = 3; i < 7; ++i) row.state.push_back(std::stod(f[static_cast<std::size_t>(i)]));
    row.reward = f[7];
    row.terminated = f[8];
    cases[f[0]].push_back(row);
  }
  return cases;
}

// Replays every row of `rows` and compares the state to 1e-12 relative (the Python reference uses
// the same IEEE doubles and libm, so agreement is usually exact; the margin allows a different
// but equivalent operation order).
void replay(const std::string& env, const Params& params, const std::vector<Row>& rows,
            double* worst) {
  auto e = Registry::global().make(env, params);
  ASSERT_FALSE(rows.empty());
  e->setState(rows[0].state);
  for (std::size_t t = 1; t < rows.size(); ++t) {
    const double action = std::stod(rows[t].action);
    const StepResult r = e->step(std::span<const double>(&action, 1));
    const auto s = e->state();
    for (std::size_t i = 0; i < 4; ++i) {
      const double want = rows[t].state[i];
      const double err = std::fabs(s[i] - want) / std::max(1.0, std::fabs(want));
      *worst = std::max(*worst, err);
      ASSERT_LE(err, 1e-12) << env << " step " << t << " variable " << i;
    }
    EXPECT_EQ(r.reward, std::stod(rows[t].reward)) << "step " << t;
    EXPECT_EQ(r.terminated, rows[t].terminated == "1") << "step " << t;
  }
}

TEST(Golden, AcrobotMatchesTheEquations) {
  const auto cases = readCases("acrobot_golden.csv");
  const std::map<std::string, Params> params{
      {"book_rk4", {}},
      {"nips_rk4", {{"dynamics", "nips"}}},
      {"book_euler4", {{"integrator", "euler"}, {"substeps", "4"}}},
      {"discrete_rk4", {{"actions", "discrete"}}},
      {"clip_wrap", {}},
      {"terminal", {}},
  };
  ASSERT_EQ(cases.size(), params.size());
  double worst = 0.0;
  for (const auto& [name, p] : params) {
    SCOPED_TRACE(name);
    replay("acrobot", p, cases.at(name), &worst);
  }
  EXPECT_EQ(cases.at("terminal").back().terminated, "1");
  RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(Golden, CartPoleMatchesTheEquations) {
  const auto cases = readCases("cartpole_golden.csv");
  const std::map<std::string, Params> params{
      {"gym_euler", {}},
      {"clsquare_rk4", {{"gravity", "9.81"}, {"integrator", "rk4"}, {"substeps", "10"}}},
      {"discrete", {{"actions", "discrete"}}},
      {"fall", {}},
  };
  ASSERT_EQ(cases.size(), params.size());
  double worst = 0.0;
  for (const auto& [name, p] : params) {
    SCOPED_TRACE(name);
    replay("cartpole", p, cases.at(name), &worst);
    EXPECT_EQ(cases.at(name).back().terminated, "1");
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
}

}  // namespace
}  // namespace gpfd::env
