// The exported C and NumPy code compute exactly what gpfd computes.
#include "gpfd/expr/export.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "gpfd/expr/eval.hpp"
#include "gpfd/expr/parse.hpp"
#include "test_genomes.hpp"

namespace gpfd::expr {
namespace {

const VariableNames kNames{"th1", "th2", "dth1"};

std::string run(const std::string& command, int& status) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
  const int raw = pclose(pipe);
  status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

// Random genomes over every operator and states with edge values, shared by both tests.
struct Cases {
  std::vector<Genome> genomes;
  std::vector<std::vector<double>> states;
};

Cases makeCases(const std::string& primitives = "all") {
  Cases c;
  Rng rng(11);
  auto space = testing::everyOperator(3, 5);
  space.primitives.functions = PrimitiveSet::named(primitives).functions;
  for (int i = 0; i < 30; ++i) c.genomes.push_back(gp::randomGenome(rng, space));
  for (int i = 0; i < 20; ++i) c.states.push_back(testing::randomState(rng, 3));
  return c;
}

// The interpreter's values, one per line, as hex floats.
std::string expected(const Cases& c) {
  std::string out;
  for (const auto& g : c.genomes) {
    std::vector<double> f(g.featureCount());
    for (const auto& s : c.states) {
      evaluate(g, s.data(), f.data());
      for (double v : f) {
        char text[64];
        std::snprintf(text, sizeof text, "%a\n", v);
        out += text;
      }
    }
  }
  return out;
}

std::string stateLiteral(const std::vector<double>& s, const char* nan, const char* inf) {
  std::string out;
  for (double v : s) {
    char text[64];
    if (std::isnan(v)) {
      std::snprintf(text, sizeof text, "%s", nan);
    } else if (std::isinf(v)) {
      std::snprintf(text, sizeof text, "%s%s", v < 0 ? "-" : "", inf);
    } else {
      std::snprintf(text, sizeof text, "%a", v);
    }
    out += std::string(out.empty() ? "" : ", ") + text;
  }
  return out;
}

// Compares outputs line by line (one value per genome, state, feature) and reports the first
// mismatch with its genome. Lines are hex floats or 64-bit patterns.
void expectSameLines(const std::string& got, const std::string& want, const Cases& c) {
  std::stringstream g(got), w(want);
  std::string gl, wl;
  std::size_t index = 0;
  for (std::size_t i = 0; i < c.genomes.size(); ++i) {
    for (std::size_t s = 0; s < c.states.size(); ++s) {
      for (std::size_t k = 0; k < c.genomes[i].featureCount(); ++k, ++index) {
        ASSERT_TRUE(std::getline(g, gl) && std::getline(w, wl)) << "output ended early";
        ASSERT_EQ(gl, wl) << "genome " << i << " feature " << k << " state " << s << ": " << gl
                          << " vs gpfd " << wl << "\n  "
                          << toInfix(c.genomes[i].feature(k), kNames);
      }
    }
  }
}

TEST(Export, CFunctionComputesTheSameValues) {
  const Cases c = makeCases();
  const std::string dir = ::testing::TempDir();
  std::string program = "#include <stdio.h>\n";
  std::string calls;
  for (std::size_t i = 0; i < c.genomes.size(); ++i) {
    std::string code = exportC(c.genomes[i], kNames);
    // Give each genome's function its own name; the helpers are shared.
    const auto at = code.find("void gpfd_features");
    if (i > 0) code = code.substr(at);
    code.replace(code.find("gpfd_features"), 13, "features" + std::to_string(i));
    program += code;
    for (const auto& s : c.states) {
      calls += "  { double s[] = {" + stateLiteral(s, "NAN", "INFINITY") +
               "}; double f[16]; features" + std::to_string(i) + "(s, f); for (int k = 0; k < " +
               std::to_string(c.genomes[i].featureCount()) + "; ++k) printf(\"%a\\n\", f[k]); }\n";
    }
  }
  program += "int main(void) {\n" + calls + "  return 0;\n}\n";
  std::ofstream(dir + "/exported.c") << program;
  int status = 0;
  const auto compile = run("cc -std=c99 -O2 -fno-builtin -ffp-contract=off -o " + dir +
                               "/exported " + dir + "/exported.c -lm 2>&1",
                           status);
  ASSERT_EQ(status, 0) << compile;
  expectSameLines(run(dir + "/exported", status), expected(c), c);
}

std::uint64_t bitsOf(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

TEST(Export, NumPyFunctionComputesTheSameValues) {
  int status = 0;
  run("/usr/bin/python3 -c 'import numpy' 2>&1", status);
  if (status != 0) GTEST_SKIP() << "Debian's python3-numpy is not installed";
  // NumPy's tanh, exp and log may differ from C's libm in the last bit, so the bit-for-bit check
  // covers the operators that IEEE 754 rounds exactly and gpfd's own sin and cos.
  const Cases c = makeCases("+,-,*,/,min,max,absdiff,sqrt,neg,abs,square,sin,cos");
  const std::string dir = ::testing::TempDir();
  // States and results cross the language boundary as 64-bit patterns: exact.
  std::string script = "import struct\n";
  for (std::size_t i = 0; i < c.genomes.size(); ++i) {
    std::string code = exportPython(c.genomes[i], kNames);
    code.replace(code.find("def features"), 12, "def features" + std::to_string(i));
    script += code + "\n";
  }
  script += "def unbits(b): return struct.unpack('<d', struct.pack('<Q', b))[0]\n";
  script += "def bits(v): return struct.unpack('<Q', struct.pack('<d', float(v)))[0]\n";
  script += "states = [\n";
  for (const auto& state : c.states) {
    script += "    [";
    for (double v : state) script += "unbits(" + std::to_string(bitsOf(v)) + "), ";
    script += "],\n";
  }
  script += "]\n";
  for (std::size_t i = 0; i < c.genomes.size(); ++i) {
    const std::string f = "features" + std::to_string(i);
    const std::string k = std::to_string(c.genomes[i].featureCount());
    script += "for s in states:\n    for v in " + f + "(np.array(s)):\n        print(bits(v))\n";
    // One float64 array, for one state and for a batch of states (the same values).
    script += "one = " + f + "(np.array(states[0]))\n";
    script += "assert isinstance(one, np.ndarray) and one.dtype == np.float64 and one.shape == (" +
              k + ",), one\n";
    script += "batch = " + f + "(np.array(states))\n";
    script += "assert batch.dtype == np.float64 and batch.shape == (len(states), " + k + ")\n";
    script += "assert (batch.view(np.uint64) == np.array([" + f +
              "(np.array(s)) for s in states]).view(np.uint64)).all()\n";
  }
  std::ofstream(dir + "/exported.py") << script;
  const auto out = run("/usr/bin/python3 " + dir + "/exported.py 2>&1", status);
  ASSERT_EQ(status, 0) << out;
  std::string want;
  for (const auto& g : c.genomes) {
    std::vector<double> f(g.featureCount());
    for (const auto& state : c.states) {
      evaluate(g, state.data(), f.data());
      for (double v : f) want += std::to_string(bitsOf(v)) + "\n";
    }
  }
  expectSameLines(out, want, c);
}

// LaTeX, like infix, never writes "- -c" or "\cdot -c": a negative constant after an operator's
// symbol is parenthesised; elsewhere (first, or an argument) it is not.
TEST(Export, LatexParenthesisesNegativeConstantsAfterAnOperator) {
  Genome g;
  g.addFeature(parseInfix("th1 - -0.139", kNames));
  g.addFeature(parseInfix("-2 * th2 + -0.5 * dth1", kNames));
  g.addFeature(parseInfix("th1 * -3 / -0", kNames));
  EXPECT_EQ(exportLatex(g, kNames),
            "\\begin{align*}\n"
            "  \\phi_{1}(s) &= \\mathit{th}_{1} - \\left(-0.139\\right) \\\\\n"
            "  \\phi_{2}(s) &= -2 \\cdot \\mathit{th}_{2} + \\left(-0.5\\right) \\cdot "
            "\\mathit{dth}_{1} \\\\\n"
            "  \\phi_{3}(s) &= \\frac{\\mathit{th}_{1} \\cdot \\left(-3\\right)}{-0}\n"
            "\\end{align*}\n");
}

}  // namespace
}  // namespace gpfd::expr
