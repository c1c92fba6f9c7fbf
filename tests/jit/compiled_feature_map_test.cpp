// CompiledFeatureMap: native when possible, a silent-to-the-caller fallback otherwise, the same
// results either way, any batch size, concurrent calls.
#include "gpfd/jit/compiled_feature_map.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <thread>
#include <vector>

#include "gpfd/expr/eval.hpp"
#include "random_genomes.hpp"

namespace gpfd::jit {
namespace {

expr::Genome sample(std::uint64_t seed, int variables = 4) {
  Rng rng(seed);
  return testing::randomGenome(rng, testing::operatorSet("all"), 6, 6, variables);
}

TEST(CompiledFeatureMap, IsNativeWhereTheJitIsAvailable) {
  const CompiledFeatureMap map(sample(1), 4);
  EXPECT_EQ(map.isNative(), jitAvailable());
  EXPECT_EQ(map.hasNativeBatch(), jitAvailable() && hostHasAvx2());
  EXPECT_EQ(map.hasNativeLaneBlocks(), jitAvailable() && hostHasAvx2());
  EXPECT_EQ(map.inputDim(), 4u);
  EXPECT_EQ(map.outputDim(), sample(1).featureCount());
}

TEST(CompiledFeatureMap, FallbackGivesTheSameFeatures) {
  if (!jitAvailable()) GTEST_SKIP() << "needs native code: this build has no JIT";
  for (int g = 0; g < 50; ++g) {
    const auto genome = sample(100 + g);
    const CompiledFeatureMap native(genome, 4);
    const CompiledFeatureMap fallback(genome, 4, CompileOptions{.native = false});
    EXPECT_FALSE(fallback.isNative());
    EXPECT_FALSE(fallback.fallbackReason().empty());
    Rng rng(g);
    const auto state = testing::randomState(rng, 4);
    std::vector<double> a(genome.featureCount()), b(genome.featureCount());
    native.evaluate(state.data(), a.data());
    fallback.evaluate(state.data(), b.data());
    for (std::size_t j = 0; j < a.size(); ++j) ASSERT_TRUE(testing::sameBits(a[j], b[j]));
  }
}

TEST(CompiledFeatureMapDeathTest, SaysOnceOnStderrWhenTheJitIsDisabled) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // A fresh process: nothing said before.
  EXPECT_EXIT(
      {
        setenv("GPFD_NO_JIT", "1", 1);
        const CompiledFeatureMap first(sample(7), 4);
        const CompiledFeatureMap second(sample(8), 4);
        std::exit(!first.isNative() && !second.isNative() ? 0 : 1);
      },
      ::testing::ExitedWithCode(0),
      // One line only, whatever the reason (GPFD_NO_JIT, or a build without the JIT).
      "^gpfd: JIT unavailable [^\n]*; features run on the interpreter\n$");
}

TEST(CompiledFeatureMap, BatchOfAnySizeWritesExactlyItsRowsAndBlocks) {
  const auto genome = sample(3);
  const std::size_t k = genome.featureCount();
  const CompiledFeatureMap map(genome, 4);
  Rng rng(3);
  for (std::size_t n = 0; n <= 13; ++n) {
    std::vector<double> states;
    for (std::size_t i = 0; i < n; ++i) {
      const auto s = testing::randomState(rng, 4);
      states.insert(states.end(), s.begin(), s.end());
    }
    std::vector<double> out(n * k + 4, 12345.0);
    map.evaluateBatch(states.data(), n, out.data());
    std::vector<double> expected(k);
    for (std::size_t i = 0; i < n; ++i) {
      expr::evaluate(genome, states.data() + 4 * i, expected.data());
      for (std::size_t j = 0; j < k; ++j) {
        ASSERT_TRUE(testing::sameBits(expected[j], out[i * k + j])) << n << " " << i;
      }
    }
    for (std::size_t j = n * k; j < out.size(); ++j) EXPECT_EQ(out[j], 12345.0);
    // Lane blocks: the whole blocks of four, and nothing beyond them.
    const auto blocks = testing::toLaneBlocks(states.data(), n, 4);
    std::fill(out.begin(), out.end(), 12345.0);
    map.evaluateLaneBlocks(blocks.data(), n / 4, out.data());
    for (std::size_t i = 0; i < n / 4 * 4; ++i) {
      expr::evaluate(genome, states.data() + 4 * i, expected.data());
      for (std::size_t j = 0; j < k; ++j) {
        ASSERT_TRUE(testing::sameBits(expected[j], testing::laneBlockValue(out.data(), i, j, k)))
            << n << " " << i;
      }
    }
    for (std::size_t j = n / 4 * 4 * k; j < out.size(); ++j) EXPECT_EQ(out[j], 12345.0);
  }
}

TEST(CompiledFeatureMap, EmptyGenomeHasNoFeatures) {
  const CompiledFeatureMap map(expr::Genome{}, 2);
  EXPECT_EQ(map.outputDim(), 0u);
  const double state[] = {1.0, 2.0};
  double sentinel = 9.0;
  map.evaluate(state, &sentinel);
  map.evaluateBatch(state, 1, &sentinel);
  const double block[8] = {1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0};
  map.evaluateLaneBlocks(block, 1, &sentinel);
  EXPECT_EQ(sentinel, 9.0);
}

TEST(CompiledFeatureMap, ConcurrentCallsAgree) {
  const auto genome = sample(11);
  const std::size_t k = genome.featureCount();
  const CompiledFeatureMap map(genome, 4);
  std::vector<std::thread> threads;
  std::vector<int> failures(4, 0);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      Rng rng(t);
      std::vector<double> a(k), b(k);
      for (int i = 0; i < 2000; ++i) {
        const auto state = testing::randomState(rng, 4);
        map.evaluate(state.data(), a.data());
        expr::evaluate(genome, state.data(), b.data());
        for (std::size_t j = 0; j < k; ++j) failures[t] += !testing::sameBits(a[j], b[j]);
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int f : failures) EXPECT_EQ(f, 0);
}

TEST(CompiledFeatureMap, ManyCompileReleaseCycles) {
  // Each map owns and releases its code; this exercises reuse of released code memory.
  const auto genome = sample(21);
  const double state[] = {0.1, 0.2, 0.3, 0.4};
  std::vector<double> expected(genome.featureCount()), got(genome.featureCount());
  expr::evaluate(genome, state, expected.data());
  for (int i = 0; i < 3000; ++i) {
    const CompiledFeatureMap map(i % 2 ? genome : sample(22 + i % 7), 4);
    if (i % 2) {
      map.evaluate(state, got.data());
      for (std::size_t j = 0; j < got.size(); ++j)
        ASSERT_TRUE(testing::sameBits(expected[j], got[j]));
    }
  }
}

}  // namespace
}  // namespace gpfd::jit
