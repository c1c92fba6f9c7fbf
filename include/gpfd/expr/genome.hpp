// expr: the genome (an individual): a variable-length list of feature functions stored as one
// contiguous prefix-order node array (the paper's linearisation, section 3) plus the feature
// boundaries.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpfd/expr/ops.hpp"

namespace gpfd::expr {

// A node of a prefix-linearised tree. The subtree rooted at index i covers [i, i + length); its
// first child starts at i + 1, each next child right after the previous child's subtree.
struct Node {
  Op op = Op::Const;
  std::uint16_t var = 0;     // Op::Var: the state variable's index.
  std::uint32_t length = 1;  // Number of nodes in the subtree rooted here.
  double value = 0.0;        // Op::Const: the constant's value (always finite).

  static Node constant(double v) { return {Op::Const, 0, 1, v}; }
  static Node variable(int index) { return {Op::Var, static_cast<std::uint16_t>(index), 1, 0.0}; }
  static Node function(Op op) { return {op, 0, 1, 0.0}; }

  friend bool operator==(const Node&, const Node&) = default;
};

using Tree = std::vector<Node>;
using TreeView = std::span<const Node>;

// Limits every genome must respect; every GP operator keeps them. Depth counts levels: a single
// terminal has depth 1, a complete binary tree of depth d has 2^d - 1 nodes.
struct GenomeLimits {
  int minFeatures = 1;
  int maxFeatures = 8;
  int maxDepth = 8;
  int maxSize = 64;  // Nodes per feature.
};

// Hard caps for any expression that reaches the system (parsed files included), whatever the
// configured limits: deeper or larger input is refused with an error.
inline constexpr int kMaxParseDepth = 64;
inline constexpr int kMaxParseSize = 1 << 16;

class Genome {
 public:
  Genome() = default;

  std::size_t featureCount() const { return starts_.size(); }
  std::size_t size() const { return nodes_.size(); }  // Total number of nodes.
  bool empty() const { return starts_.empty(); }
  TreeView feature(std::size_t k) const {
    return TreeView(nodes_).subspan(starts_[k], nodes_[starts_[k]].length);
  }
  std::vector<Tree> features() const;
  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<std::uint32_t>& starts() const { return starts_; }

  // Appends a feature; its subtree lengths must be consistent (see recomputeLengths).
  void addFeature(TreeView tree);
  static Genome fromFeatures(const std::vector<Tree>& features);

  friend bool operator==(const Genome&, const Genome&) = default;

 private:
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> starts_;
};

// Sets every node's subtree length from the arities; returns false when the sequence is not one
// well-formed prefix tree.
bool recomputeLengths(std::span<Node> tree);
// Number of levels of a well-formed tree (1 for a terminal).
int depth(TreeView tree);
// Depth of the node at `index` below the root (the root is at level 1).
int levelOf(TreeView tree, std::size_t index);
// Structural check: lengths consistent, variable indices below `variableCount`, constants finite.
// Returns an empty string when valid, else what is wrong.
std::string checkTree(TreeView tree, int variableCount);
// checkTree for every feature plus the limits; empty when valid.
std::string checkGenome(const Genome& genome, const GenomeLimits& limits, int variableCount);

}  // namespace gpfd::expr
