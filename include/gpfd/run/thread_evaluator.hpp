// run: fitness evaluation in parallel on threads (oneTBB). Results are identical to
// SerialEvaluator's for any thread count, because each genome's RNG comes from its own seed.
#pragma once

#include "gpfd/gp/evaluator.hpp"

namespace gpfd::run {

class ThreadEvaluator final : public gp::Evaluator {
 public:
  // threads <= 0: all hardware threads.
  ThreadEvaluator(gp::FitnessFunction fitness, int threads);
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override;
  int threads() const { return threads_; }

 private:
  gp::FitnessFunction fitness_;
  int threads_;
};

}  // namespace gpfd::run
