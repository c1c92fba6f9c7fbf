// io: plots through gnuplot (Debian's gnuplot-nox): line plots with optional 95% bands, written
// as PNG and SVG next to the data and the script that made them.
#pragma once

#include <string>
#include <vector>

namespace gpfd::io {

struct Series {
  std::string title;
  std::vector<double> x, y;
  std::vector<double> low, high;  // Optional band (same size as y), e.g. a 95% interval.
  bool dashed = false;            // A dashed line (a second family of series).
  bool markers = false;           // Points on the line (a single-point series shows as a dot).
  int colour = 0;                 // gnuplot line colour index; 0: by position.
};

struct LinePlot {
  std::string title, xlabel, ylabel;
  std::vector<Series> series;
  bool logY = false;
  std::string key = "bottom right";  // Where gnuplot puts the legend.
};

// Writes BASE.dat, BASE.gp, and renders BASE.png and BASE.svg (BASE is a path without
// extension). Returns false, with a warning on stderr, when gnuplot is missing or fails; the data
// and script are written either way. Throws InputError when a file cannot be written.
bool plotLines(const std::string& base, const LinePlot& plot);

}  // namespace gpfd::io
