// `gpfd train` end to end: outputs, row 0, errors with exit code 2 and nothing written.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

int run(const std::string& args) {
  const std::string command = std::string(GPFD_BINARY) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("gpfd_rl_train_test_" + name);
  fs::remove_all(dir);
  return dir;
}

TEST(TrainCommand, WritesCurveAndWeights) {
  const fs::path dir = freshDir("ok");
  ASSERT_EQ(run("train cartpole --param updates=3 --seed 4 --quiet --out " + dir.string()), 0);
  std::ifstream csv(dir / "curve.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header, "update,episodes,steps,mean_return");
  int rows = 0;
  while (std::getline(csv, line)) {
    if (rows == 0) {
      EXPECT_EQ(line.rfind("0,10,", 0), 0u) << line;
    }
    ++rows;
  }
  EXPECT_EQ(rows, 4);
  std::ifstream json(dir / "weights.json");
  std::stringstream text;
  text << json.rdbuf();
  EXPECT_NE(text.str().find("\"values\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(TrainCommand, BadInputExitsWithTwoAndWritesNothing) {
  const fs::path dir = freshDir("bad");
  EXPECT_EQ(run("train cartpole --param no_such_setting=1 --out " + dir.string()), 2);
  EXPECT_EQ(run("train cartpole --param updates=-1 --out " + dir.string()), 2);
  EXPECT_EQ(run("train cartpole --learner lpi --out " + dir.string()), 2);
  EXPECT_EQ(run("train cartpole --features /nonexistent/f.txt --out " + dir.string()), 2);
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
