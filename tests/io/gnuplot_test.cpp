// plotLines: the data (one block per series, bands when given), the script, and the pictures
// when gnuplot is there.
#include "gpfd/io/gnuplot.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "gpfd/util/error.hpp"

namespace gpfd::io {
namespace {

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Gnuplot, WritesDataScriptAndPictures) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "gnuplot_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  LinePlot plot{"It's a title", "x", "y", {}, false};
  plot.series.push_back({"with band", {0, 1}, {1, 2}, {0.5, 1.5}, {1.5, 2.5}});
  plot.series.push_back({"plain", {0, 1}, {3, 4}, {}, {}, true});
  const bool rendered = plotLines((dir / "plot").string(), plot);

  EXPECT_EQ(read(dir / "plot.dat"),
            "# with band\n0 1 0.5 1.5\n1 2 1.5 2.5\n\n\n# plain\n0 3 3 3\n1 4 4 4\n\n\n");
  const std::string script = read(dir / "plot.gp");
  EXPECT_NE(script.find("set title 'It''s a title'"), std::string::npos) << script;
  EXPECT_NE(script.find("filledcurves"), std::string::npos);
  EXPECT_NE(script.find("dt 2"), std::string::npos);  // The dashed series.
  if (rendered) {
    EXPECT_GT(std::filesystem::file_size(dir / "plot.png"), 0u);
    EXPECT_GT(std::filesystem::file_size(dir / "plot.svg"), 0u);
  }
}

TEST(Gnuplot, AnUnwritableDirectoryIsAnInputError) {
  LinePlot plot{"t", "x", "y", {}, false};
  EXPECT_THROW(plotLines("/nonexistent/dir/plot", plot), InputError);
}

}  // namespace
}  // namespace gpfd::io
