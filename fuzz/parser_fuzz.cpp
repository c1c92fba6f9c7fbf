// libFuzzer harness for the feature parsers: any input either parses, or fails with an
// InputError; whatever parses prints and parses back to the same tree, and evaluates to a finite
// value. The first byte picks infix, S-expression or a whole features file. Long inputs (up to
// 1 MB, see make_long_seeds.py and docs/expressions.md) must take under a second each.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "gpfd/expr/eval.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/expr/parse.hpp"
#include "gpfd/expr/simplify.hpp"
#include "gpfd/util/error.hpp"

namespace {

const gpfd::expr::VariableNames kNames{"a", "b", "x"};

void check(const gpfd::expr::Tree& tree) {
  using namespace gpfd::expr;
  if (parseInfix(toInfix(tree, kNames), kNames) != tree) std::abort();
  if (parseSexpr(toSexpr(tree, kNames), kNames) != tree) std::abort();
  const double state[] = {0.5, -1e308, std::nan("")};
  const double value = evaluate(tree, state);
  if (!std::isfinite(value) || evaluate(simplify(tree), state) != value) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    switch (data[0] % 3) {
      case 0:
        check(gpfd::expr::parseInfix(text, kNames));
        break;
      case 1:
        check(gpfd::expr::parseSexpr(text, kNames));
        break;
      default: {
        // The whole file is parsed; the round trips are checked on its first features only, so
        // that a 1 MB file of 100,000 features stays well under the 1 s budget of an input.
        const auto file = gpfd::expr::parseFeaturesFile(text, "fuzz", kNames);
        for (std::size_t k = 0; k < std::min<std::size_t>(file.genome.featureCount(), 64); ++k) {
          const auto f = file.genome.feature(k);
          check(gpfd::expr::Tree(f.begin(), f.end()));
        }
      }
    }
  } catch (const gpfd::InputError&) {
  }
  return 0;
}
