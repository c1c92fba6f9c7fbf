// Differential tests: the fast interpreter, the scalar JIT and the AVX2 batch kernels (state rows
// and lane blocks) agree bit for bit with the reference interpreter (expr::evaluate) on random
// genomes and edge-case states.
#include <gtest/gtest.h>

#include <vector>

#include "gpfd/expr/eval.hpp"
#include "gpfd/expr/features_file.hpp"
#include "gpfd/gp/init.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "gpfd/jit/fast_interpreter.hpp"
#include "random_genomes.hpp"

namespace gpfd::jit {
namespace {

using testing::sameBits;

constexpr int kGenomesPerSet = 2500;  // 4 operator sets: 10,000 genomes.
constexpr int kVariables = 5;
constexpr int kStates = 9;  // Not a multiple of 4: the batch tail runs the scalar code.

void expectAgreement(const expr::Genome& genome, const std::vector<double>& states,
                     const std::string& where) {
  const std::size_t k = genome.featureCount();
  const std::size_t n = states.size() / kVariables;
  std::vector<double> reference(n * k);
  for (std::size_t i = 0; i < n; ++i) {
    expr::evaluate(genome, states.data() + i * kVariables, reference.data() + i * k);
  }
  const FastInterpretedFeatureMap fast(genome, kVariables);
  const CompiledFeatureMap compiled(genome, kVariables);
  if (jitAvailable()) {
    ASSERT_TRUE(compiled.isNative()) << compiled.fallbackReason();
  }
  std::vector<double> viaFast(n * k), viaJit(n * k), viaBatch(n * k, -7.0);
  for (std::size_t i = 0; i < n; ++i) {
    fast.evaluate(states.data() + i * kVariables, viaFast.data() + i * k);
    compiled.evaluate(states.data() + i * kVariables, viaJit.data() + i * k);
  }
  compiled.evaluateBatch(states.data(), n, viaBatch.data());
  // The lane-block kernel and the default lane-block evaluation (the fast interpreter's), on the
  // whole blocks of four states.
  const std::size_t groups = n / 4;
  const auto blocks = testing::toLaneBlocks(states.data(), n, kVariables);
  std::vector<double> viaBlocks(groups * 4 * k, -7.0), viaFastBlocks(groups * 4 * k, -7.0);
  compiled.evaluateLaneBlocks(blocks.data(), groups, viaBlocks.data());
  fast.evaluateLaneBlocks(blocks.data(), groups, viaFastBlocks.data());
  for (std::size_t l = 0; l < groups * 4; ++l) {
    for (std::size_t j = 0; j < k; ++j) {
      const double expected = reference[l * k + j];
      const double got = testing::laneBlockValue(viaBlocks.data(), l, j, k);
      ASSERT_TRUE(sameBits(expected, got)) << where << " lane blocks: state " << l << " feature "
                                           << j << " " << expected << " vs " << got;
      ASSERT_TRUE(sameBits(expected, testing::laneBlockValue(viaFastBlocks.data(), l, j, k)))
          << where << " default lane blocks: state " << l << " feature " << j;
    }
  }
  for (std::size_t j = 0; j < n * k; ++j) {
    ASSERT_TRUE(std::isfinite(reference[j])) << where;
    ASSERT_TRUE(sameBits(reference[j], viaFast[j]))
        << where << " fast: value " << j << " " << reference[j] << " vs " << viaFast[j];
    ASSERT_TRUE(sameBits(reference[j], viaJit[j]))
        << where << " jit: value " << j << " " << reference[j] << " vs " << viaJit[j];
    ASSERT_TRUE(sameBits(reference[j], viaBatch[j]))
        << where << " batch: value " << j << " " << reference[j] << " vs " << viaBatch[j];
  }
}

class Differential : public ::testing::TestWithParam<std::string> {};

TEST_P(Differential, AgreesWithReferenceInterpreterBitForBit) {
  const auto ops = testing::operatorSet(GetParam());
  for (int g = 0; g < kGenomesPerSet; ++g) {
    Rng rng(deriveSeed(2024, GetParam().size(), g));
    const expr::Genome genome = testing::randomGenome(rng, ops, 8, 7, kVariables);
    std::vector<double> states;
    for (int i = 0; i < kStates; ++i) {
      const auto s = testing::randomState(rng, kVariables);
      states.insert(states.end(), s.begin(), s.end());
    }
    expectAgreement(genome, states, GetParam() + " genome " + std::to_string(g));
    if (::testing::Test::HasFatalFailure()) return;
  }
}

INSTANTIATE_TEST_SUITE_P(OperatorSets, Differential,
                         ::testing::ValuesIn(testing::operatorSetNames()));

// Every variable takes every edge value in turn, the others fixed at ordinary values.
TEST(DifferentialEdges, EveryEdgeValueInEveryVariable) {
  for (const auto& set : testing::operatorSetNames()) {
    const auto ops = testing::operatorSet(set);
    for (int g = 0; g < 50; ++g) {
      Rng rng(deriveSeed(77, set.size(), g));
      const expr::Genome genome = testing::randomGenome(rng, ops, 6, 6, kVariables);
      std::vector<double> states;
      for (int v = 0; v < kVariables; ++v) {
        for (double edge : testing::edgeValues()) {
          std::vector<double> s{0.5, -1.5, 3.0, 1e-3, 42.0};
          s[v] = edge;
          states.insert(states.end(), s.begin(), s.end());
        }
      }
      expectAgreement(genome, states, set + " edge genome " + std::to_string(g));
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
}

// The batch kernel computes sin(x) and cos(x) of one value by one call: pairs in either order,
// several pairs, a pair member used only inside a later feature, pairs among many live values
// (spilled around the calls), an unpaired sin beside them; on random and edge-case states.
TEST(DifferentialTrigPairs, SinAndCosOfOneValueAgreeBitForBit) {
  const std::vector<std::string> sets{
      "sin(x0)\ncos(x0)\n",
      "cos(x1)\nsin(x1)\nsin(x2)\n",
      "sin(x0 + x1) * x2\ncos(x0 + x1)\nsin(x3)\ncos(x3) - sin(x0)\ncos(x0)\n",
      "x0 * x1\nx1 * x2\nx2 * x3\nx3 * x4\nx4 * x0\nx0 + x2\nx1 + x3\nx2 + x4\n"
      "x0 - x3\nx1 - x4\nx2 - x0\nx3 - x1\nx4 - x2\nsin(x0 * x1 + x4)\n"
      "cos(x0 * x1 + x4) + x0 * x1 + x1 * x2 + x2 * x3 + x3 * x4 + x4 * x0 + x0 + x2 + x1 + x3\n",
      "sin(sin(x0)) + cos(sin(x0))\ncos(x0)\n",
  };
  const expr::VariableNames names{"x0", "x1", "x2", "x3", "x4"};
  Rng rng(31);
  for (const auto& text : sets) {
    const expr::Genome genome = expr::parseFeaturesFile(text, "pairs", names).genome;
    std::vector<double> states;
    for (int i = 0; i < 4 * kStates; ++i) {
      const auto s = testing::randomState(rng, kVariables);
      states.insert(states.end(), s.begin(), s.end());
    }
    for (double edge : testing::edgeValues()) {
      for (int v = 0; v < kVariables; ++v) states.push_back(v == 0 ? edge : 0.25 * v);
    }
    expectAgreement(genome, states, text);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

// GP's own generation-0 genomes (the learner choice's random sets draw them too), one map after
// another, both batch layouts on buffers of exactly their size, the two layouts agreeing: under
// valgrind (scripts/valgrind-jit, --smc-check=all: docs/jit.md) no kernel may touch a byte past
// them.
TEST(DifferentialGpGenomes, BatchKernelsStayWithinBuffersOfTheirSize) {
  for (const char* set : {"control", "arithmetic"}) {
    for (int dim = 1; dim <= 3; ++dim) {
      gp::SearchSpace space;
      space.primitives = expr::PrimitiveSet::named(set);
      space.variableCount = dim;
      Rng rng(1234 + static_cast<std::uint64_t>(dim));
      for (int g = 0; g < 800; ++g) {
        const auto genome = gp::randomGenome(rng, space);
        const CompiledFeatureMap compiled(genome, static_cast<std::size_t>(dim));
        const std::size_t k = genome.featureCount(), d = static_cast<std::size_t>(dim);
        for (const std::size_t n : {4, 8}) {
          const std::vector<double> states(n * d, 0.5);  // Lane blocks and state rows alike.
          std::vector<double> viaBlocks(n * k), viaRows(n * k);
          compiled.evaluateLaneBlocks(states.data(), n / 4, viaBlocks.data());
          compiled.evaluateBatch(states.data(), n, viaRows.data());
          for (std::size_t l = 0; l < n; ++l) {
            for (std::size_t j = 0; j < k; ++j) {
              ASSERT_TRUE(
                  sameBits(viaRows[l * k + j], testing::laneBlockValue(viaBlocks.data(), l, j, k)))
                  << set << " genome " << g << " state " << l << " feature " << j;
            }
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace gpfd::jit
