// Hostile genomes (as a crafted features file could produce): out-of-range variables, malformed
// lengths, non-finite constants, huge and deep trees are refused before any code is generated,
// and compiled code touches nothing outside its state and feature buffers.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <limits>
#include <vector>

#include "gpfd/expr/eval.hpp"
#include "gpfd/jit/compiled_feature_map.hpp"
#include "random_genomes.hpp"

namespace gpfd::jit {
namespace {

using expr::Node;
using expr::Op;

expr::Tree make(std::vector<Node> nodes) {
  expr::recomputeLengths(nodes);
  return nodes;
}

// A chain of `levels` nested negations over x0.
expr::Tree chain(int levels) {
  std::vector<Node> nodes(static_cast<std::size_t>(levels - 1), Node::function(Op::Neg));
  nodes.push_back(Node::variable(0));
  return make(nodes);
}

// A complete binary tree of additions over x0 with `levels` levels.
void complete(int levels, std::vector<Node>& out) {
  if (levels == 1) {
    out.push_back(Node::variable(0));
    return;
  }
  out.push_back(Node::function(Op::Add));
  complete(levels - 1, out);
  complete(levels - 1, out);
}

TEST(Malicious, OutOfRangeVariablesAreRejectedBeforeCompiling) {
  for (int var : {3, 4, 1000, 65535}) {
    const auto genome = expr::Genome::fromFeatures(
        {make({Node::function(Op::Add), Node::variable(0), Node::variable(var)})});
    EXPECT_THROW(CompiledFeatureMap(genome, 3), LowerError) << var;
    EXPECT_THROW(lower(genome, 3), LowerError) << var;
  }
}

TEST(Malicious, MalformedLengthsAreRejected) {
  expr::Genome genome;
  std::vector<Node> nodes{Node::function(Op::Add), Node::variable(0), Node::variable(1)};
  nodes[0].length = 1000;  // Claims more nodes than exist.
  genome.addFeature(nodes);
  EXPECT_THROW(CompiledFeatureMap(genome, 2), LowerError);
  expr::Genome truncated;
  std::vector<Node> half{Node::function(Op::Add), Node::variable(0)};
  half[0].length = 2;  // A binary node with one child.
  truncated.addFeature(half);
  EXPECT_THROW(CompiledFeatureMap(truncated, 2), LowerError);
}

TEST(Malicious, NonFiniteConstantsAreRejected) {
  for (double c :
       {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    const auto genome = expr::Genome::fromFeatures({make({Node::constant(c)})});
    EXPECT_THROW(CompiledFeatureMap(genome, 1), LowerError);
  }
}

TEST(Malicious, NestingBeyondTheDepthLimitIsRefused) {
  EXPECT_THROW(CompiledFeatureMap(expr::Genome::fromFeatures({chain(kMaxLowerDepth + 1)}), 1),
               LowerError);
  // At the limit it compiles and agrees with the reference.
  const auto genome = expr::Genome::fromFeatures({chain(kMaxLowerDepth)});
  const CompiledFeatureMap map(genome, 1);
  const double state[] = {-3.25};
  double out = 0.0;
  map.evaluate(state, &out);
  EXPECT_EQ(out, expr::evaluate(genome.feature(0), state));
}

TEST(Malicious, HugeGenomesAreRefused) {
  std::vector<Node> big;
  complete(17, big);  // 131071 nodes, 17 levels.
  ASSERT_GT(big.size(), kMaxLowerNodes);
  expr::recomputeLengths(big);
  EXPECT_THROW(CompiledFeatureMap(expr::Genome::fromFeatures({big}), 1), LowerError);
  // Many features, each small, beyond the limit on features.
  std::vector<expr::Tree> many(kMaxLowerFeatures + 1, make({Node::variable(0)}));
  EXPECT_THROW(CompiledFeatureMap(expr::Genome::fromFeatures(many), 1), LowerError);
}

// Buffers placed against inaccessible pages: any read or write outside them faults.
class GuardedBuffer {
 public:
  GuardedBuffer() {
    page_ = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    void* p = mmap(nullptr, 3 * page_, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    EXPECT_NE(p, MAP_FAILED);
    base_ = static_cast<char*>(p);
    EXPECT_EQ(mprotect(base_ + page_, page_, PROT_READ | PROT_WRITE), 0);
  }
  ~GuardedBuffer() { munmap(base_, 3 * page_); }
  // `count` doubles ending exactly at the inaccessible page, or starting right after one.
  double* atEnd(std::size_t count) { return reinterpret_cast<double*>(base_ + 2 * page_) - count; }
  double* atStart() { return reinterpret_cast<double*>(base_ + page_); }

 private:
  std::size_t page_ = 0;
  char* base_ = nullptr;
};

TEST(Malicious, CompiledCodeStaysInsideItsBuffers) {
  if (!jitAvailable()) GTEST_SKIP() << "needs native code: this build has no JIT";
  constexpr int kVariables = 3;
  GuardedBuffer states, features;
  for (int g = 0; g < 300; ++g) {
    Rng rng(deriveSeed(5, g));
    const auto genome = testing::randomGenome(rng, testing::operatorSet("all"), 8, 6, kVariables);
    const std::size_t k = genome.featureCount();
    const CompiledFeatureMap map(genome, kVariables);
    ASSERT_TRUE(map.isNative());
    std::vector<double> expected(8 * k);
    for (bool end : {true, false}) {
      double* s = end ? states.atEnd(8 * kVariables) : states.atStart();
      double* f = end ? features.atEnd(8 * k) : features.atStart();
      for (int i = 0; i < 8 * kVariables; ++i) s[i] = rng.normal();
      for (int i = 0; i < 8; ++i) expr::evaluate(genome, s + i * kVariables, &expected[i * k]);
      map.evaluate(s, f);
      for (std::size_t j = 0; j < k; ++j) ASSERT_TRUE(testing::sameBits(expected[j], f[j]));
      map.evaluateBatch(s, 5, f);
      for (std::size_t j = 0; j < 5 * k; ++j) ASSERT_TRUE(testing::sameBits(expected[j], f[j]));
      // Two lane blocks of four states, read and written at the edges of the guarded buffers.
      const auto blocks = testing::toLaneBlocks(s, 8, kVariables);
      std::copy(blocks.begin(), blocks.end(), s);
      map.evaluateLaneBlocks(s, 2, f);
      for (std::size_t l = 0; l < 8; ++l) {
        for (std::size_t j = 0; j < k; ++j) {
          ASSERT_TRUE(testing::sameBits(expected[l * k + j], testing::laneBlockValue(f, l, j, k)));
        }
      }
    }
  }
}

// Many values alive at once: the compiler spills them, and refuses (falling back to the
// interpreter, still correct) only beyond its documented frame limit.
expr::Genome manyLiveValues(int count) {
  std::vector<expr::Tree> features;
  std::vector<Node> total;
  for (int i = 0; i < count; ++i) {
    features.push_back(
        make({Node::function(Op::Mul), Node::variable(i % 3), Node::constant(1.0 + i)}));
  }
  // The last feature adds all of them up again, as a balanced tree, last term first.
  std::vector<std::vector<Node>> layer;
  for (int i = count; i-- > 0;) layer.push_back(features[i]);
  while (layer.size() > 1) {
    std::vector<std::vector<Node>> next;
    for (std::size_t j = 0; j + 1 < layer.size(); j += 2) {
      std::vector<Node> sum{Node::function(Op::Add)};
      sum.insert(sum.end(), layer[j].begin(), layer[j].end());
      sum.insert(sum.end(), layer[j + 1].begin(), layer[j + 1].end());
      next.push_back(sum);
    }
    if (layer.size() % 2) next.push_back(layer.back());
    layer = next;
  }
  features.push_back(make(layer[0]));
  return expr::Genome::fromFeatures(features);
}

TEST(Malicious, HeavySpillingIsCorrectOrRefused) {
  if (!jitAvailable()) GTEST_SKIP() << "needs native code: this build has no JIT";
  for (int count : {40, 200, 700}) {
    const auto genome = manyLiveValues(count);
    const CompiledFeatureMap map(genome, 3);
    if (count <= 200) {
      EXPECT_TRUE(map.isNative()) << map.fallbackReason();
    }
    if (count == 700) {
      EXPECT_FALSE(map.isNative());
    }
    const double state[] = {0.5, -2.0, 1e300};
    std::vector<double> expected(genome.featureCount()), got(genome.featureCount());
    expr::evaluate(genome, state, expected.data());
    map.evaluate(state, got.data());
    for (std::size_t j = 0; j < got.size(); ++j)
      ASSERT_TRUE(testing::sameBits(expected[j], got[j]));
    std::vector<double> states(8 * 3), batch(8 * got.size());
    for (int i = 0; i < 8; ++i) std::copy(state, state + 3, states.begin() + 3 * i);
    map.evaluateBatch(states.data(), 8, batch.data());
    for (std::size_t j = 0; j < batch.size(); ++j) {
      ASSERT_TRUE(testing::sameBits(expected[j % got.size()], batch[j]));
    }
    const auto blocks = testing::toLaneBlocks(states.data(), 8, 3);
    map.evaluateLaneBlocks(blocks.data(), 2, batch.data());
    for (std::size_t j = 0; j < batch.size(); ++j) {
      ASSERT_TRUE(testing::sameBits(expected[j / 4 % got.size()], batch[j]));
    }
  }
}

}  // namespace
}  // namespace gpfd::jit
