#include "gpfd/run/thread_evaluator.hpp"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace gpfd::run {

ThreadEvaluator::ThreadEvaluator(gp::FitnessFunction fitness, int threads)
    : fitness_(std::move(fitness)),
      threads_(threads > 0 ? threads : tbb::info::default_concurrency()) {}

std::vector<double> ThreadEvaluator::evaluate(const std::vector<const expr::Genome*>& genomes,
                                              const std::vector<std::uint64_t>& seeds) {
  std::vector<double> out(genomes.size());
  tbb::task_arena arena(threads_);
  arena.execute([&] {
    // Grain size 1: one fitness evaluation is long (many episodes), so balance beats overhead.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, genomes.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          Rng rng(seeds[i]);
                          out[i] = fitness_(*genomes[i], rng);
                        }
                      });
  });
  return out;
}

}  // namespace gpfd::run
