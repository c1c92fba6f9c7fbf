// experiments: the built-in supervised feature-discovery task that proves the GP loop end to end.
// Target y = 3 x0 x1 - 2 sin(x2) + 0.5 on states drawn uniformly from [-2, 2]^3; fitness of a
// genome = R^2 of the ordinary least-squares fit of y on its features plus a bias.
#pragma once

#include <cstdint>
#include <vector>

#include "gpfd/expr/genome.hpp"
#include "gpfd/expr/print.hpp"
#include "gpfd/gp/evolution.hpp"

namespace gpfd::experiments {

class ToyTask {
 public:
  // `samples` states drawn with Rng(seed).
  ToyTask(int samples, std::uint64_t seed);

  static double target(const double* x);
  static const expr::VariableNames& variableNames();
  // R^2 in (-inf, 1]; -inf when the fit is not finite.
  double rSquared(const expr::Genome& genome) const;

 private:
  int samples_;
  std::vector<double> states_;  // samples x 3, row-major.
  std::vector<double> targets_;
};

// The default GP settings of `gpfd evolve-toy`.
gp::GpConfig toyGpConfig(std::uint64_t seed);
gp::SearchSpace toySearchSpace();

}  // namespace gpfd::experiments
