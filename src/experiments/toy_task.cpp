#include "gpfd/experiments/toy_task.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "gpfd/expr/eval.hpp"

namespace gpfd::experiments {

ToyTask::ToyTask(int samples, std::uint64_t seed) : samples_(samples) {
  Rng rng(seed);
  states_.resize(static_cast<std::size_t>(samples) * 3);
  for (auto& v : states_) v = rng.uniform(-2.0, 2.0);
  for (int s = 0; s < samples; ++s) targets_.push_back(target(&states_[3 * s]));
}

double ToyTask::target(const double* x) { return 3.0 * x[0] * x[1] - 2.0 * std::sin(x[2]) + 0.5; }

const expr::VariableNames& ToyTask::variableNames() {
  static const expr::VariableNames names{"x0", "x1", "x2"};
  return names;
}

double ToyTask::rSquared(const expr::Genome& genome) const {
  const auto k = static_cast<Eigen::Index>(genome.featureCount());
  Eigen::MatrixXd design(samples_, k + 1);
  Eigen::VectorXd y(samples_);
  std::vector<double> row(genome.featureCount());
  for (int s = 0; s < samples_; ++s) {
    expr::evaluate(genome, &states_[3 * s], row.data());
    for (Eigen::Index j = 0; j < k; ++j) design(s, j) = row[j];
    design(s, k) = 1.0;
    y(s) = targets_[s];
  }
  const Eigen::VectorXd weights = design.completeOrthogonalDecomposition().solve(y);
  const double sse = (design * weights - y).squaredNorm();
  const double sst = (y.array() - y.mean()).matrix().squaredNorm();
  const double r2 = 1.0 - sse / sst;
  return std::isfinite(r2) ? std::min(r2, 1.0) : -std::numeric_limits<double>::infinity();
}

gp::GpConfig toyGpConfig(std::uint64_t seed) {
  gp::GpConfig config;
  config.population = 200;
  config.generations = 40;
  config.sizePenalty = 1e-5;
  config.seed = seed;
  return config;
}

gp::SearchSpace toySearchSpace() {
  gp::SearchSpace space;
  space.primitives = expr::PrimitiveSet::named("control");
  space.variableCount = 3;
  space.limits = {1, 6, 6, 32};
  return space;
}

}  // namespace gpfd::experiments
