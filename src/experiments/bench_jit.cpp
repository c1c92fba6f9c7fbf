// gpfd bench jit: the paper's Figure 3 reproduced and extended (docs/jit.md). Writes
// DIR/jit.csv (the {+,-,*,/} set), DIR/jit_unary.csv (with sin, cos, sqrt), both with the columns
// depth,nodes,method,ns_per_call,compile_us, DIR/jit.png and DIR/jit.svg (speed-ups over the tree
// interpreter, gnuplot) and DIR/jit_summary.txt (the ratios of the targets).
#include "gpfd/experiments/bench_jit.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "gpfd/experiments/aot_reference.hpp"
#include "gpfd/experiments/figure3.hpp"
#include "gpfd/io/gnuplot.hpp"
#include "gpfd/jit/x86_compiler.hpp"
#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::experiments {
namespace {

namespace fs = std::filesystem;

void parseDepths(const std::string& text, Figure3Options& options) {
  int lo = 0, hi = 0;
  char dash = 0;
  std::istringstream in(text);
  if (!(in >> lo)) throw InputError("depths must look like 2-8 or 5", "--depths " + text);
  hi = lo;
  if (in >> dash) {
    if (dash != '-' || !(in >> hi)) throw InputError("depths must look like 2-8", "--depths");
  }
  in >> std::ws;
  if (!in.eof() || lo < 1 || hi < lo || hi > 16) {
    throw InputError("depths must be a range within 1-16", "--depths " + text);
  }
  options.minDepth = lo;
  options.maxDepth = hi;
}

std::string number(double x) {
  if (std::isnan(x)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", x);
  return buffer;
}

std::string csv(const std::vector<Figure3Row>& rows, BenchSet set) {
  std::string text = "depth,nodes,method,ns_per_call,compile_us\n";
  for (const auto& r : rows) {
    if (r.set != set) continue;
    text += std::to_string(r.depth) + "," + number(r.nodes) + "," + r.method + "," +
            number(r.nsPerCall) + "," + number(r.compileUs) + "\n";
  }
  return text;
}

using Table = std::map<std::pair<int, int>, std::map<std::string, Figure3Row>>;

Table tabulate(const std::vector<Figure3Row>& rows) {
  Table table;
  for (const auto& r : rows) table[{static_cast<int>(r.set), r.depth}][r.method] = r;
  return table;
}

double ns(const Table& t, BenchSet set, int depth, const std::string& method) {
  const auto it = t.find({static_cast<int>(set), depth});
  if (it == t.end()) return NAN;
  const auto m = it->second.find(method);
  return m == it->second.end() ? NAN : m->second.nsPerCall;
}

// jit.png / jit.svg: speed-ups over the tree-walking interpreter per depth, solid lines for
// {+, -, *, /}, dashed with sin, cos, sqrt, and the paper's reported point.
void plot(const fs::path& dir, const Table& table, const Figure3Options& o) {
  io::LinePlot figure{"Speed-up over the tree-walking interpreter (Figure 3 of Girgin and Preux)",
                      "depth of the complete tree",
                      "speed-up",
                      {},
                      true,
                      "top left"};
  for (BenchSet set : {BenchSet::Arithmetic, BenchSet::Unary}) {
    int colour = 0;
    for (const char* m : {"jit", "aot", "batch", "interp"}) {
      io::Series series;
      series.colour = ++colour;  // The same colour for a method in both sets.
      series.title =
          std::string(m) + (set == BenchSet::Arithmetic ? " {+,-,*,/}" : " +sin,cos,sqrt");
      series.dashed = set == BenchSet::Unary;
      series.markers = true;
      for (int d = o.minDepth; d <= o.maxDepth; ++d) {
        const double x = ns(table, set, d, "tree") / ns(table, set, d, m);
        if (std::isnan(x)) continue;
        series.x.push_back(d);
        series.y.push_back(x);
      }
      if (!series.x.empty()) figure.series.push_back(series);
    }
  }
  io::Series paper;
  paper.title = "paper, GNU Lightning (about 75x at depth 8)";
  paper.x = {8};
  paper.y = {75};
  paper.markers = true;
  paper.colour = 7;
  figure.series.push_back(paper);
  io::plotLines((dir / "jit").string(), figure);
}

std::string summary(const Table& t, const Figure3Options& o, const MemoryCheck& mem) {
  std::ostringstream s;
  s << "gpfd bench jit: seed " << o.seed << ", " << o.calls << " calls, " << o.runs
    << " runs (thread CPU time)\n";
  for (BenchSet set : {BenchSet::Arithmetic, BenchSet::Unary}) {
    s << "\n"
      << benchSetName(set) << " set\n"
      << "depth nodes   tree/jit  tree/interp  jit/aot  jit/batch  compile_us\n";
    for (int d = o.minDepth; d <= o.maxDepth; ++d) {
      const auto it = t.find({static_cast<int>(set), d});
      if (it == t.end()) continue;
      const double jitNs = ns(t, set, d, "jit");
      char line[160];
      std::snprintf(line, sizeof line, "%5d %6.0f %9.2f %11.2f %8.3f %10.2f %11.2f\n", d,
                    it->second.at("jit").nodes, ns(t, set, d, "tree") / jitNs,
                    ns(t, set, d, "tree") / ns(t, set, d, "interp"), jitNs / ns(t, set, d, "aot"),
                    jitNs / ns(t, set, d, "batch"), it->second.at("jit").compileUs);
      s << line;
    }
  }
  // The paper's two sizes (63 and 255 nodes) when measured, else the smallest and largest trees.
  const int small = o.minDepth <= 6 && 6 <= o.maxDepth ? 6 : o.minDepth;
  const int large = o.minDepth <= 8 && 8 <= o.maxDepth ? 8 : o.maxDepth;
  const auto jitRow = [&](int d) {
    return t.at({static_cast<int>(BenchSet::Arithmetic), d}).at("jit");
  };
  s << "\ncompile time, " << number(jitRow(small).nodes) << " nodes (depth " << small
    << "): " << number(jitRow(small).compileUs) << " us";
  if (large != small) {
    s << "; " << number(jitRow(large).nodes) << " nodes (depth " << large
      << "): " << number(jitRow(large).compileUs) << " us; ratio "
      << number(jitRow(large).compileUs / jitRow(small).compileUs);
  }
  s << "\n";
  s << "code pages: "
    << (jit::jitUsesDualMapping() ? "dual-mapped (read-execute view, separate read-write view)"
                                  : "read-write-execute (no dual mapping on this system)")
    << "; AVX2 batch kernel: " << (jit::hostHasAvx2() ? "yes" : "no") << "\n";
  if (mem.cycles > 0) {
    s << "resident memory over " << mem.cycles << " compile/release cycles: " << mem.rssBeforeKiB
      << " KiB -> " << mem.rssAfterKiB << " KiB (" << (mem.rssAfterKiB - mem.rssBeforeKiB)
      << " KiB)\n";
  }
  return s.str();
}

}  // namespace

void runBenchJit(const BenchJitArgs& args) {
  if (!jit::jitAvailable()) {
    throw InputError(
        "the JIT benchmark needs the JIT, which this build lacks (GPFD_WITH_JIT=OFF "
        "or not x86-64)",
        "gpfd bench jit");
  }
  Figure3Options options;
  parseDepths(args.depths, options);
  options.calls = args.calls;
  options.runs = args.runs;
  options.seed = args.seed;
  const fs::path dir(args.out);
  createDirectories(args.out);

  // AOT rows only for the seed the reference code was generated with.
  AotLookup aot;
  if (args.seed == aotSeed()) {
    aot = [](BenchSet set, int depth, int run) -> jit::ScalarFunction {
      for (const auto& f : aotFunctions()) {
        if (f.set == set && f.depth == depth && f.run == run) return f.function;
      }
      return nullptr;
    };
  }
  const auto rows = runFigure3(options, aot);
  const Table table = tabulate(rows);
  writeFileAtomically((dir / "jit.csv").string(), csv(rows, BenchSet::Arithmetic));
  writeFileAtomically((dir / "jit_unary.csv").string(), csv(rows, BenchSet::Unary));
  const MemoryCheck memory = args.memoryCycles > 0
                                 ? measureCompileReleaseMemory(args.memoryCycles, args.seed)
                                 : MemoryCheck{};
  const std::string text = summary(table, options, memory);
  writeFileAtomically((dir / "jit_summary.txt").string(), text);
  plot(dir, table, options);
  if (args.print) std::fputs(text.c_str(), stdout);
}

}  // namespace gpfd::experiments
