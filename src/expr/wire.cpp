#include "gpfd/expr/wire.hpp"

#include <fmt/format.h>

#include <bit>

namespace gpfd::expr::wire {
namespace {

constexpr char kMagic[2] = {'g', 'w'};
constexpr std::uint8_t kOpMask = 0x3f;
constexpr std::uint8_t kHasVar = 0x40;
constexpr std::uint8_t kHasValue = 0x80;
static_assert(kOpCount <= kOpMask + 1, "op codes must fit in the op byte's low 6 bits");

template <typename T>
void putLittle(std::string& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<char>(static_cast<std::uint8_t>(value >> (8 * i))));
  }
}

// Reads little-endian numbers from bytes[at...]; WireError at the end of the bytes.
class Cursor {
 public:
  Cursor(std::string_view bytes, std::size_t& at) : bytes_(bytes), at_(at) {}
  template <typename T>
  T take() {
    need(sizeof(T));
    T value = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      value |=
          static_cast<T>(static_cast<T>(static_cast<std::uint8_t>(bytes_[at_ + i])) << (8 * i));
    }
    at_ += sizeof(T);
    return value;
  }
  std::size_t left() const { return bytes_.size() - at_; }
  void need(std::size_t n) const {
    if (left() < n) {
      throw WireError(fmt::format("the genome's bytes end early ({} bytes needed, {} given)",
                                  at_ + n, bytes_.size()));
    }
  }

 private:
  std::string_view bytes_;
  std::size_t& at_;
};

}  // namespace

void appendGenome(std::string& out, const Genome& genome) {
  out.append(kMagic, sizeof kMagic);
  out.push_back(static_cast<char>(kWireVersion));
  putLittle(out, static_cast<std::uint32_t>(genome.featureCount()));
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    const auto tree = genome.feature(k);
    putLittle(out, static_cast<std::uint32_t>(tree.size()));
    for (const Node& node : tree) {
      const auto bits = std::bit_cast<std::uint64_t>(node.value);
      putLittle(out, static_cast<std::uint8_t>(static_cast<std::uint8_t>(node.op) |
                                               (node.var != 0 ? kHasVar : 0) |
                                               (bits != 0 ? kHasValue : 0)));
      if (node.var != 0) putLittle(out, node.var);
      if (bits != 0) putLittle(out, bits);
    }
  }
}

std::string encodeGenome(const Genome& genome) {
  std::string out;
  appendGenome(out, genome);
  return out;
}

std::vector<Tree> readTrees(std::string_view bytes, std::size_t& at) {
  Cursor cursor(bytes, at);
  cursor.need(sizeof kMagic + 1);
  if (bytes[at] != kMagic[0] || bytes[at + 1] != kMagic[1]) {
    throw WireError("the bytes are not a genome (no 'gw' mark at their start)");
  }
  at += sizeof kMagic;
  const auto version = cursor.take<std::uint8_t>();
  if (version != kWireVersion) {
    throw WireError(fmt::format(
        "the genome was sent in wire format version {}, this build of gpfd reads version {}: "
        "run the same gpfd on every process",
        version, kWireVersion));
  }
  const auto count = cursor.take<std::uint32_t>();
  // Each feature takes at least 5 bytes: a corrupt count fails here, before any allocation.
  if (count > cursor.left() / 5) throw WireError(fmt::format("bad feature count {}", count));
  std::vector<Tree> trees;
  trees.reserve(count);
  for (std::uint32_t k = 0; k < count; ++k) {
    const auto size = cursor.take<std::uint32_t>();
    if (size == 0 || size > static_cast<std::uint32_t>(kMaxParseSize) || size > cursor.left()) {
      throw WireError(fmt::format("feature {} has a bad node count {}", k + 1, size));
    }
    Tree tree(size);
    for (Node& node : tree) {
      const auto code = cursor.take<std::uint8_t>();
      if ((code & kOpMask) >= kOpCount) {
        throw WireError(fmt::format("unknown operator code {}", code & kOpMask));
      }
      node.op = static_cast<Op>(code & kOpMask);
      node.var = (code & kHasVar) ? cursor.take<std::uint16_t>() : std::uint16_t{0};
      node.value = std::bit_cast<double>((code & kHasValue) ? cursor.take<std::uint64_t>() : 0);
      if (((code & kHasVar) && node.var == 0) ||
          ((code & kHasValue) && std::bit_cast<std::uint64_t>(node.value) == 0)) {
        throw WireError("a node sends a zero field it should leave out");
      }
    }
    if (!recomputeLengths(tree)) {
      throw WireError(fmt::format("feature {} is not a well-formed prefix tree", k + 1));
    }
    trees.push_back(std::move(tree));
  }
  return trees;
}

Genome readGenome(std::string_view bytes, std::size_t& at, int variableCount) {
  Genome genome;
  const auto trees = readTrees(bytes, at);
  for (std::size_t k = 0; k < trees.size(); ++k) {
    if (const std::string problem = checkTree(trees[k], variableCount); !problem.empty()) {
      throw WireError(fmt::format("bad genome: feature {}: {}", k + 1, problem));
    }
    genome.addFeature(trees[k]);
  }
  return genome;
}

Genome decodeGenome(std::string_view bytes, int variableCount) {
  std::size_t at = 0;
  Genome genome = readGenome(bytes, at, variableCount);
  if (at != bytes.size()) {
    throw WireError(fmt::format("{} bytes follow the genome", bytes.size() - at));
  }
  return genome;
}

}  // namespace gpfd::expr::wire
