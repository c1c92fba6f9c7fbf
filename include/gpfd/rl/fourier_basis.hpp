// rl: the Fourier basis (Konidaris, Osentoski & Thomas 2011, "Value function approximation in
// reinforcement learning using the Fourier basis", AAAI): phi_c(s) = cos(pi c . x), with x the
// state scaled to [0, 1]^d and c over {0..order}^d (full coupling), or only the c with one
// non-zero entry (independent, d * order + 1 terms) where the full basis would be too large.
// A generic basis to compare GP's handful of readable features against.
#pragma once

#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/features/feature_map.hpp"

namespace gpfd::rl {

using env::StateRange;

class FourierBasis final : public features::FeatureMap {
 public:
  enum class Coupling { Full, Independent };
  // `ranges` scale each variable to [0, 1] (values outside are clamped). Full coupling has
  // (order + 1)^d terms, the constant included.
  FourierBasis(std::vector<StateRange> ranges, int order, Coupling coupling);
  // Full coupling when it has at most `maxTerms` terms, else independent.
  static FourierBasis automatic(std::vector<StateRange> ranges, int order, int maxTerms = 1024);

  std::size_t inputDim() const override { return ranges_.size(); }
  std::size_t outputDim() const override { return coefficients_.size() / ranges_.size(); }
  void evaluate(const double* state, double* features) const override;
  Coupling coupling() const { return coupling_; }

 private:
  std::vector<StateRange> ranges_;
  int order_;
  Coupling coupling_;
  std::vector<double> coefficients_;  // outputDim() x d, row-major: the vectors c.
};

}  // namespace gpfd::rl
