#include "gpfd/gp/init.hpp"

#include <algorithm>

namespace gpfd::gp {
namespace {

std::size_t terminalChoices(const SearchSpace& space) {
  return static_cast<std::size_t>(space.variableCount) + space.primitives.constants.size() +
         (space.primitives.ephemeral ? 1 : 0);
}

void grow(Rng& rng, const SearchSpace& space, int depth, bool full, expr::Tree& out) {
  const auto& functions = space.primitives.functions;
  bool terminal = depth <= 1 || functions.empty();
  if (!terminal && !full) {
    const double t = static_cast<double>(terminalChoices(space));
    terminal = rng.uniform() < t / (t + static_cast<double>(functions.size()));
  }
  if (terminal) {
    out.push_back(randomTerminal(rng, space));
    return;
  }
  const expr::Node node = randomFunction(rng, space);
  out.push_back(node);
  for (int c = 0; c < expr::arity(node.op); ++c) grow(rng, space, depth - 1, full, out);
}

}  // namespace

expr::Node randomTerminal(Rng& rng, const SearchSpace& space) {
  const auto& p = space.primitives;
  std::size_t pick = rng.below(terminalChoices(space));
  if (pick < static_cast<std::size_t>(space.variableCount)) {
    return expr::Node::variable(static_cast<int>(pick));
  }
  pick -= static_cast<std::size_t>(space.variableCount);
  if (pick < p.constants.size()) return expr::Node::constant(p.constants[pick]);
  return expr::Node::constant(rng.uniform(p.ephemeralLow, p.ephemeralHigh));
}

expr::Node randomFunction(Rng& rng, const SearchSpace& space, int arity) {
  const auto candidates =
      arity < 0 ? space.primitives.functions : space.primitives.functionsOfArity(arity);
  return expr::Node::function(candidates[rng.below(candidates.size())]);
}

expr::Tree randomTree(Rng& rng, const SearchSpace& space, int depth, bool full) {
  expr::Tree tree;
  grow(rng, space, depth, full, tree);
  expr::recomputeLengths(tree);
  return tree;
}

expr::Genome randomGenome(Rng& rng, const SearchSpace& space) {
  const auto& limits = space.limits;
  const int maxDepth = std::max(1, std::min(space.initMaxDepth, limits.maxDepth));
  const int minDepth = std::clamp(space.initMinDepth, 1, maxDepth);
  const int maxFeatures =
      std::max(limits.minFeatures, std::min(space.initMaxFeatures, limits.maxFeatures));
  const int count = rng.between(limits.minFeatures, maxFeatures);
  expr::Genome genome;
  for (int k = 0; k < count; ++k) {
    const bool full = rng.bernoulli(0.5);
    int depth = rng.between(minDepth, maxDepth);
    expr::Tree tree = randomTree(rng, space, depth, full);
    // Shrink the depth until the tree fits the size limit (a terminal always does).
    while (static_cast<int>(tree.size()) > limits.maxSize) {
      depth = std::max(1, depth - 1);
      tree = randomTree(rng, space, depth, full);
    }
    genome.addFeature(tree);
  }
  return genome;
}

}  // namespace gpfd::gp
