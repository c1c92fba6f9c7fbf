#include "gpfd/io/gnuplot.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "gpfd/util/atomic_file.hpp"

namespace gpfd::io {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string shellQuoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

bool plotLines(const std::string& base, const LinePlot& plot) {
  // One data block per series, separated by two blank lines (gnuplot's `index`).
  std::string data;
  for (const auto& s : plot.series) {
    data += "# " + s.title + "\n";
    const bool band = s.low.size() == s.y.size() && s.high.size() == s.y.size();
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      data += fmt::format("{} {} {} {}\n", s.x[i], s.y[i], band ? s.low[i] : s.y[i],
                          band ? s.high[i] : s.y[i]);
    }
    data += "\n\n";
  }
  writeFileAtomically(base + ".dat", data);

  const std::string dat = std::filesystem::path(base + ".dat").filename().string();
  std::string body = fmt::format(
      "set title {}\nset xlabel {}\nset ylabel {}\nset key {}\nset grid\n{}", quoted(plot.title),
      quoted(plot.xlabel), quoted(plot.ylabel), plot.key, plot.logY ? "set logscale y\n" : "");
  std::string bands, lines;
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const auto& s = plot.series[i];
    const int colour = s.colour > 0 ? s.colour : static_cast<int>(i) + 1;
    if (!s.low.empty()) {
      bands += fmt::format(
          "{}{} index {} using 1:3:4 with filledcurves lc {} fs transparent solid "
          "0.2 notitle",
          bands.empty() ? "" : ", ", quoted(dat), i, colour);
    }
    lines += fmt::format("{}{} index {} using 1:2 with {} lw 2 lc {}{} title {}",
                         lines.empty() ? "" : ", ", quoted(dat), i,
                         s.markers ? "linespoints pt 7" : "lines", colour, s.dashed ? " dt 2" : "",
                         quoted(s.title));
  }
  const std::string plotLine = "plot " + (bands.empty() ? lines : bands + ", " + lines) + "\n";
  const std::string png = std::filesystem::path(base + ".png").filename().string();
  const std::string svg = std::filesystem::path(base + ".svg").filename().string();
  const std::string script = body + "set terminal pngcairo size 900,600\nset output " +
                             quoted(png) + "\n" + plotLine + "set terminal svg size 900,600\n" +
                             "set output " + quoted(svg) + "\n" + plotLine;
  writeFileAtomically(base + ".gp", script);

  const std::string dir = std::filesystem::path(base).parent_path().string();
  const std::string command =
      fmt::format("cd {} && gnuplot {} 2>/dev/null", shellQuoted(dir.empty() ? "." : dir),
                  shellQuoted(std::filesystem::path(base + ".gp").filename().string()));
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "warning: gnuplot failed or is missing; the plot script is %s.gp\n",
                 base.c_str());
    return false;
  }
  return true;
}

}  // namespace gpfd::io
