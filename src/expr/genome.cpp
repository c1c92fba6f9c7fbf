#include "gpfd/expr/genome.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace gpfd::expr {

std::vector<Tree> Genome::features() const {
  std::vector<Tree> out;
  out.reserve(featureCount());
  for (std::size_t k = 0; k < featureCount(); ++k) {
    auto f = feature(k);
    out.emplace_back(f.begin(), f.end());
  }
  return out;
}

void Genome::addFeature(TreeView tree) {
  starts_.push_back(static_cast<std::uint32_t>(nodes_.size()));
  nodes_.insert(nodes_.end(), tree.begin(), tree.end());
}

Genome Genome::fromFeatures(const std::vector<Tree>& features) {
  Genome g;
  for (const auto& f : features) g.addFeature(f);
  return g;
}

bool recomputeLengths(std::span<Node> tree) {
  // Scan right to left; the stack holds the lengths of the complete subtrees to the right.
  std::vector<std::uint32_t> stack;
  stack.reserve(tree.size());
  for (std::size_t i = tree.size(); i-- > 0;) {
    const int a = arity(tree[i].op);
    if (static_cast<int>(stack.size()) < a) return false;
    std::uint32_t length = 1;
    for (int c = 0; c < a; ++c) {
      length += stack.back();
      stack.pop_back();
    }
    tree[i].length = length;
    stack.push_back(length);
  }
  return stack.size() == 1;
}

int depth(TreeView tree) {
  // Right to left: the stack holds the depths of the complete subtrees to the right.
  std::vector<int> stack;
  stack.reserve(tree.size());
  for (std::size_t i = tree.size(); i-- > 0;) {
    int d = 0;
    for (int c = 0; c < arity(tree[i].op); ++c) {
      d = std::max(d, stack.back());
      stack.pop_back();
    }
    stack.push_back(d + 1);
  }
  return stack.empty() ? 0 : stack.back();
}

int levelOf(TreeView tree, std::size_t index) {
  int level = 1;
  std::size_t i = 0;
  while (i != index) {
    // Descend into the child whose subtree contains index.
    std::size_t child = i + 1;
    while (child + tree[child].length <= index) child += tree[child].length;
    i = child;
    ++level;
  }
  return level;
}

std::string checkTree(TreeView tree, int variableCount) {
  if (tree.empty()) return "empty feature";
  if (tree[0].length != tree.size()) return "subtree lengths do not match the tree";
  std::vector<Node> copy(tree.begin(), tree.end());
  if (!recomputeLengths(copy)) return "malformed prefix tree";
  for (std::size_t i = 0; i < tree.size(); ++i) {
    const Node& n = tree[i];
    if (static_cast<int>(n.op) >= kOpCount) return "unknown operator code";
    if (n.length != copy[i].length) return "subtree lengths do not match the tree";
    if (n.op == Op::Var && n.var >= variableCount) {
      return "variable index " + std::to_string(n.var) + " out of range (the problem has " +
             std::to_string(variableCount) + " variables)";
    }
    if (n.op == Op::Const && !std::isfinite(n.value)) return "non-finite constant";
  }
  return {};
}

std::string checkGenome(const Genome& genome, const GenomeLimits& limits, int variableCount) {
  const int count = static_cast<int>(genome.featureCount());
  if (count < limits.minFeatures || count > limits.maxFeatures) {
    return std::to_string(count) + " features, outside [" + std::to_string(limits.minFeatures) +
           ", " + std::to_string(limits.maxFeatures) + "]";
  }
  std::size_t total = 0;
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    const std::size_t start = genome.starts()[k];
    if (start >= genome.size() || start + genome.nodes()[start].length > genome.size()) {
      return "feature boundaries out of range";
    }
    auto f = genome.feature(k);
    total += f.size();
    const std::string where = "feature " + std::to_string(k + 1) + ": ";
    if (auto problem = checkTree(f, variableCount); !problem.empty()) return where + problem;
    if (static_cast<int>(f.size()) > limits.maxSize) {
      return where + "size " + std::to_string(f.size()) + " exceeds " +
             std::to_string(limits.maxSize);
    }
    if (depth(f) > limits.maxDepth) {
      return where + "depth " + std::to_string(depth(f)) + " exceeds " +
             std::to_string(limits.maxDepth);
    }
  }
  if (total != genome.size()) return "feature boundaries do not cover the node array";
  return {};
}

}  // namespace gpfd::expr
