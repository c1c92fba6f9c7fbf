// The one genome wire format (gpfd/expr/wire.hpp): exact round trips, every node kind, the
// golden record the Python test reads too (tests/python/test_wire.py), and clear errors for
// truncated, corrupt or other-version bytes.
#include "gpfd/expr/wire.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>

#include "gpfd/gp/init.hpp"
#include "test_genomes.hpp"

namespace gpfd::expr {
namespace {

std::uint64_t bitsOf(double v) { return std::bit_cast<std::uint64_t>(v); }

Genome withLengths(std::vector<Tree> features) {
  for (Tree& tree : features) EXPECT_TRUE(recomputeLengths(tree));
  return Genome::fromFeatures(features);
}

// The golden genome over (x, y, z): tests/data/wire/genome-v1.bin holds its record.
Genome golden() {
  return withLengths({{Node::function(Op::Add), Node::variable(0), Node::function(Op::Mul),
                       Node::constant(2.5), Node::function(Op::Sin), Node::variable(2)},
                      {Node::constant(-0.0)},
                      {Node::function(Op::Div), Node::variable(1),
                       Node::constant(std::numeric_limits<double>::denorm_min())},
                      {Node::function(Op::Tanh), Node::constant(-1.0 / 3.0)}});
}

std::string goldenBytes() {
  std::ifstream in(GPFD_TEST_DATA_DIR "/wire/genome-v1.bin", std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void expectSameBits(const Genome& a, const Genome& b) {
  ASSERT_EQ(a.starts(), b.starts());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Node &x = a.nodes()[i], &y = b.nodes()[i];
    EXPECT_EQ(x.op, y.op);
    EXPECT_EQ(x.var, y.var);
    EXPECT_EQ(x.length, y.length);
    EXPECT_EQ(bitsOf(x.value), bitsOf(y.value)) << "node " << i;
  }
}

TEST(Wire, GoldenRecordIsStable) {
  const std::string bytes = goldenBytes();
  if (std::getenv("GPFD_WRITE_WIRE_GOLDEN")) {  // Regenerate after a deliberate format change.
    std::ofstream(GPFD_TEST_DATA_DIR "/wire/genome-v1.bin", std::ios::binary)
        << wire::encodeGenome(golden());
    GTEST_SKIP() << "wrote the golden record";
  }
  ASSERT_FALSE(bytes.empty());
  EXPECT_EQ(wire::encodeGenome(golden()), bytes);
  expectSameBits(wire::decodeGenome(bytes, 3), golden());
}

TEST(Wire, RandomGenomesRoundTripBitForBit) {
  Rng rng(35);
  const auto space = testing::everyOperator(5);
  for (int i = 0; i < 300; ++i) {
    const Genome genome = gp::randomGenome(rng, space);
    const std::string bytes = wire::encodeGenome(genome);
    const Genome back = wire::decodeGenome(bytes, 5);
    expectSameBits(back, genome);
    EXPECT_EQ(wire::encodeGenome(back), bytes);
  }
}

TEST(Wire, EveryNodeKindAndEdgeConstant) {
  std::vector<Tree> features;
  for (int op = 2; op < kOpCount; ++op) {  // Every function, over the widest variable index.
    Tree tree{Node::function(static_cast<Op>(op))};
    for (int c = 0; c < arity(static_cast<Op>(op)); ++c) tree.push_back(Node::variable(65535 - c));
    features.push_back(tree);
  }
  const double edges[] = {0.0,
                          -0.0,
                          std::numeric_limits<double>::denorm_min(),
                          -std::numeric_limits<double>::denorm_min(),
                          std::numeric_limits<double>::min(),
                          std::numeric_limits<double>::max(),
                          -std::numeric_limits<double>::max(),
                          0.1};
  for (double v : edges) features.push_back({Node::constant(v)});
  features.push_back({Node::variable(0)});
  const Genome genome = withLengths(features);
  expectSameBits(wire::decodeGenome(wire::encodeGenome(genome), 65536), genome);
}

TEST(Wire, NaNPayloadsTravelBitForBitAndAreRefusedAsConstants) {
  const double nans[] = {std::bit_cast<double>(std::uint64_t{0x7ff0000000000001}),
                         std::bit_cast<double>(std::uint64_t{0xfff8000000dead01}),
                         std::numeric_limits<double>::infinity()};
  for (double v : nans) {
    const std::string bytes = wire::encodeGenome(withLengths({{Node::constant(v)}}));
    std::size_t at = 0;
    const auto trees = wire::readTrees(bytes, at);
    EXPECT_EQ(at, bytes.size());
    EXPECT_EQ(bitsOf(trees.at(0).at(0).value), bitsOf(v));
    // The engine never holds a non-finite constant: a genome with one is refused.
    try {
      wire::decodeGenome(bytes, 1);
      ADD_FAILURE() << "decoded a non-finite constant";
    } catch (const wire::WireError& e) {
      EXPECT_NE(std::string(e.what()).find("non-finite constant"), std::string::npos);
    }
  }
  // A node field the engine does not read still travels exactly.
  Node odd = Node::variable(1);
  odd.value = std::bit_cast<double>(std::uint64_t{0x7ff4000000000abc});
  const Genome genome = withLengths({{odd}});
  expectSameBits(wire::decodeGenome(wire::encodeGenome(genome), 2), genome);
}

TEST(Wire, EmptyGenome) {
  const std::string bytes = wire::encodeGenome(Genome{});
  EXPECT_EQ(bytes.size(), 7u);
  EXPECT_TRUE(wire::decodeGenome(bytes, 0).empty());
}

TEST(Wire, RecordsFollowEachOther) {
  std::string bytes;
  wire::appendGenome(bytes, golden());
  wire::appendGenome(bytes, Genome{});
  wire::appendGenome(bytes, golden());
  std::size_t at = 0;
  expectSameBits(wire::readGenome(bytes, at, 3), golden());
  EXPECT_TRUE(wire::readGenome(bytes, at, 3).empty());
  expectSameBits(wire::readGenome(bytes, at, 3), golden());
  EXPECT_EQ(at, bytes.size());
}

std::string errorOf(const std::string& bytes, int variables = 3) {
  try {
    wire::decodeGenome(bytes, variables);
  } catch (const wire::WireError& e) {
    return e.what();
  }
  return {};
}

TEST(Wire, OtherVersionNamesBoth) {
  std::string bytes = goldenBytes();
  bytes[2] = 2;
  const std::string what = errorOf(bytes);
  EXPECT_NE(what.find("wire format version 2"), std::string::npos) << what;
  EXPECT_NE(what.find("reads version 1"), std::string::npos) << what;
  EXPECT_NE(errorOf("GP" + bytes.substr(2)).find("not a genome"), std::string::npos);
}

TEST(Wire, TruncationAtEveryByteIsAnError) {
  const std::string bytes = goldenBytes();
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_FALSE(errorOf(bytes.substr(0, n)).empty()) << n << " bytes";
  }
  EXPECT_NE(errorOf(bytes + "x").find("1 bytes follow"), std::string::npos);
  // The message says how many bytes the record needed and how many it was given.
  const std::string what = errorOf(bytes.substr(0, bytes.size() - 1));
  EXPECT_NE(what.find(fmt::format("({} bytes needed, {} given)", bytes.size(), bytes.size() - 1)),
            std::string::npos)
      << what;
}

TEST(Wire, BadFieldsAreErrors) {
  const std::string bytes = goldenBytes();
  EXPECT_NE(errorOf(bytes, 2).find("out of range"), std::string::npos);  // z over (x, y).
  std::string op = bytes;
  op[11] = static_cast<char>(kOpCount);  // The first node's op code.
  EXPECT_NE(errorOf(op).find("unknown operator code"), std::string::npos) << errorOf(op);
  std::string count = bytes;
  count[6] = 0x7f;  // A feature count near 2^31.
  EXPECT_NE(errorOf(count).find("bad feature count"), std::string::npos) << errorOf(count);
}

// Random corruption never crashes nor reads past the end (ASan checks the reads); bytes that
// still decode are the canonical record of what they decode to.
TEST(Wire, RandomCorruptionIsAnErrorOrACanonicalRecord) {
  Rng rng(7);
  const auto space = testing::everyOperator(4);
  int decoded = 0;
  for (int i = 0; i < 4000; ++i) {
    std::string bytes = wire::encodeGenome(gp::randomGenome(rng, space));
    const int flips = 1 + static_cast<int>(rng.below(3));
    for (int f = 0; f < flips; ++f) {
      bytes[rng.below(bytes.size())] ^= static_cast<char>(1 + rng.below(255));
    }
    if (rng.bernoulli(0.3)) bytes.resize(rng.below(bytes.size()));
    try {
      const Genome genome = wire::decodeGenome(bytes, 4);
      EXPECT_EQ(wire::encodeGenome(genome), bytes);
      ++decoded;
    } catch (const wire::WireError& e) {
      EXPECT_NE(std::string(e.what()), "");
    }
  }
  EXPECT_LT(decoded, 4000);
}

}  // namespace
}  // namespace gpfd::expr
