#include "gpfd/gp/operators.hpp"

#include <algorithm>

#include "gpfd/gp/init.hpp"

namespace gpfd::gp {
namespace {

using expr::Genome;
using expr::Tree;
using expr::TreeView;

// A position in a genome: feature k, node i within it.
struct Point {
  std::size_t feature;
  std::size_t node;
};

bool fits(TreeView tree, const SearchSpace& space) {
  return static_cast<int>(tree.size()) <= space.limits.maxSize &&
         expr::depth(tree) <= space.limits.maxDepth;
}

// A node of feature k: an internal one with probability kInternalNodeBias when there is one.
std::size_t pickNode(Rng& rng, TreeView tree, bool internalOnly = false) {
  std::vector<std::size_t> internal;
  for (std::size_t i = 0; i < tree.size(); ++i) {
    if (!expr::isTerminal(tree[i].op)) internal.push_back(i);
  }
  if (internalOnly || (!internal.empty() && rng.bernoulli(kInternalNodeBias))) {
    return internal.empty() ? 0 : internal[rng.below(internal.size())];
  }
  return rng.below(tree.size());
}

Point pickPoint(Rng& rng, const Genome& g) {
  const std::size_t k = rng.below(g.featureCount());
  return {k, pickNode(rng, g.feature(k))};
}

// `tree` with the subtree at `at` replaced by `branch`.
Tree splice(TreeView tree, std::size_t at, TreeView branch) {
  Tree out(tree.begin(), tree.begin() + static_cast<std::ptrdiff_t>(at));
  out.insert(out.end(), branch.begin(), branch.end());
  out.insert(out.end(), tree.begin() + static_cast<std::ptrdiff_t>(at + tree[at].length),
             tree.end());
  expr::recomputeLengths(out);
  return out;
}

Genome replaceFeature(const Genome& g, std::size_t k, TreeView tree) {
  Genome out;
  for (std::size_t f = 0; f < g.featureCount(); ++f) out.addFeature(f == k ? tree : g.feature(f));
  return out;
}

TreeView branchAt(TreeView tree, std::size_t at) { return tree.subspan(at, tree[at].length); }

}  // namespace

Offspring subtreeCrossover(Rng& rng, const Genome& a, const Genome& b, const SearchSpace& space) {
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
    const Point pa = pickPoint(rng, a);
    const Point pb = pickPoint(rng, b);
    const TreeView fa = a.feature(pa.feature), fb = b.feature(pb.feature);
    Tree childA = splice(fa, pa.node, branchAt(fb, pb.node));
    Tree childB = splice(fb, pb.node, branchAt(fa, pa.node));
    if (fits(childA, space) && fits(childB, space)) {
      return {replaceFeature(a, pa.feature, childA), replaceFeature(b, pb.feature, childB)};
    }
  }
  return {a, b};
}

Offspring featureListCrossover(Rng& rng, const Genome& a, const Genome& b,
                               const SearchSpace& space) {
  const std::size_t n = a.featureCount(), m = b.featureCount();
  if (n < 2 || m < 2) return {a, b};
  const auto& limits = space.limits;
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
    const std::size_t i = 1 + rng.below(n - 1);
    const std::size_t j = 1 + rng.below(m - 1);
    const auto countA = static_cast<int>(i + m - j), countB = static_cast<int>(j + n - i);
    if (countA < limits.minFeatures || countA > limits.maxFeatures || countB < limits.minFeatures ||
        countB > limits.maxFeatures) {
      continue;
    }
    Genome childA, childB;
    for (std::size_t f = 0; f < i; ++f) childA.addFeature(a.feature(f));
    for (std::size_t f = j; f < m; ++f) childA.addFeature(b.feature(f));
    for (std::size_t f = 0; f < j; ++f) childB.addFeature(b.feature(f));
    for (std::size_t f = i; f < n; ++f) childB.addFeature(a.feature(f));
    return {std::move(childA), std::move(childB)};
  }
  return {a, b};
}

Genome nodeMutation(Rng& rng, const Genome& g, const SearchSpace& space) {
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
    const std::size_t k = rng.below(g.featureCount());
    const TreeView tree = g.feature(k);
    const std::size_t at = rng.below(tree.size());
    const expr::Node old = tree[at];
    const int a = expr::arity(old.op);
    expr::Node replacement = a == 0 ? randomTerminal(rng, space) : randomFunction(rng, space, a);
    replacement.length = old.length;
    if (replacement.op == old.op && replacement.var == old.var && replacement.value == old.value) {
      continue;  // The same node: try again for a real change.
    }
    Tree out(tree.begin(), tree.end());
    out[at] = replacement;
    return replaceFeature(g, k, out);
  }
  return g;
}

Genome treeMutation(Rng& rng, const Genome& g, const SearchSpace& space) {
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
    const Point p = pickPoint(rng, g);
    const TreeView tree = g.feature(p.feature);
    const Tree branch = randomTree(rng, space, rng.between(1, space.mutationDepth), false);
    Tree out = splice(tree, p.node, branch);
    if (fits(out, space)) return replaceFeature(g, p.feature, out);
  }
  return g;
}

Genome shrinkage(Rng& rng, const Genome& g, const SearchSpace& space) {
  std::vector<std::size_t> withOperators;
  for (std::size_t k = 0; k < g.featureCount(); ++k) {
    if (g.feature(k).size() > 1) withOperators.push_back(k);
  }
  if (withOperators.empty()) return g;
  const std::size_t k = withOperators[rng.below(withOperators.size())];
  const TreeView tree = g.feature(k);
  const std::size_t at = pickNode(rng, tree, true);
  std::size_t child = at + 1;
  for (std::size_t c = rng.below(static_cast<std::size_t>(expr::arity(tree[at].op))); c > 0; --c) {
    child += tree[child].length;
  }
  Tree out = splice(tree, at, branchAt(tree, child));
  (void)space;  // Shrinking never breaks a limit.
  return replaceFeature(g, k, out);
}

}  // namespace gpfd::gp
