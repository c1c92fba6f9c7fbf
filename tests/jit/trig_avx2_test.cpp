// The batch kernel's 4-lane sin and cos agree with expr::trig bit for bit, on random and edge
// arguments, including lanes beyond the large-argument bound mixed with ordinary ones.
#include "gpfd/jit/trig_avx2.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "gpfd/expr/trig.hpp"

namespace gpfd::jit {
namespace {

#if defined(__x86_64__)  // The 4-lane kernel exists only there (with or without the JIT).

std::vector<double> arguments() {
  std::vector<double> xs{0.0,
                         -0.0,
                         5e-324,
                         -5e-324,
                         1e-300,
                         0x1p-27,
                         -0x1p-27,
                         0x1.fffffffffffffp-28,
                         1e6,
                         -1e6,
                         std::nextafter(1e6, 2e6),
                         1e300,
                         -1.7976931348623157e308,
                         NAN,
                         INFINITY,
                         -INFINITY,
                         0.7853981633974483,
                         1.5707963267948966,
                         3.141592653589793};
  std::mt19937_64 rng(3);
  for (double range : {1e-6, 1.0, 10.0, 1e4, 1e6, 1e8}) {
    std::uniform_real_distribution<double> uniform(-range, range);
    for (int i = 0; i < 20000; ++i) xs.push_back(uniform(rng));
  }
  for (int i = 0; i < 20000; ++i) xs.push_back(std::bit_cast<double>(rng()));  // Any bits.
  for (int k = -500; k <= 500; ++k) {
    const double m = k * 1.5707963267948966;
    xs.insert(xs.end(), {m, std::nextafter(m, 1e9), std::nextafter(m, -1e9)});
  }
  while (xs.size() % 4 != 0) xs.push_back(1.0);
  return xs;
}

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) ||
         (std::isnan(a) && std::isnan(b));
}

TEST(TrigAvx2, LanesMatchTheScalarFunctionsBitForBit) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "needs AVX2, which this CPU lacks";
  const auto xs = arguments();
  for (std::size_t i = 0; i < xs.size(); i += 4) {
    double s[4], c[4];
    for (int j = 0; j < 4; ++j) s[j] = c[j] = xs[i + j];
    sin4Avx2(s);
    cos4Avx2(c);
    for (int j = 0; j < 4; ++j) {
      ASSERT_TRUE(sameBits(s[j], expr::trig::sin(xs[i + j]))) << "sin " << xs[i + j];
      ASSERT_TRUE(sameBits(c[j], expr::trig::cos(xs[i + j]))) << "cos " << xs[i + j];
    }
  }
}

#else

TEST(TrigAvx2, LanesMatchTheScalarFunctionsBitForBit) {
  GTEST_SKIP() << "needs native x86-64 code: the AVX2 kernel exists only on x86-64";
}

#endif

}  // namespace
}  // namespace gpfd::jit
