// gp: the batch-evaluation interface behind which fitness runs serially, on threads or on MPI
// (pagmo2's batch evaluator is the model).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "gpfd/expr/genome.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::gp {

// Fitness of one genome; larger is better. `rng` is the genome's own stream, seeded from
// (run seed, generation, index), so the result never depends on who computes it. A non-finite
// result counts as the worst fitness.
using FitnessFunction = std::function<double(const expr::Genome&, Rng&)>;

class Evaluator {
 public:
  virtual ~Evaluator() = default;
  // fitness[i] = f(*genomes[i], Rng(seeds[i])). Same inputs => same outputs, whatever the
  // evaluator.
  virtual std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                                       const std::vector<std::uint64_t>& seeds) = 0;
};

class SerialEvaluator final : public Evaluator {
 public:
  explicit SerialEvaluator(FitnessFunction fitness) : fitness_(std::move(fitness)) {}
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override {
    std::vector<double> out(genomes.size());
    for (std::size_t i = 0; i < genomes.size(); ++i) {
      Rng rng(seeds[i]);
      out[i] = fitness_(*genomes[i], rng);
    }
    return out;
  }

 private:
  FitnessFunction fitness_;
};

}  // namespace gpfd::gp
