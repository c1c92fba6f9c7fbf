// python: the Python executor's fitness evaluations (python_evaluator.hpp).
#include "python_evaluator.hpp"

#include <fmt/format.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <stdexcept>
#include <string_view>

#include "gpfd/expr/wire.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/util/rng.hpp"
#include "lockstep_group.hpp"
#include "trial_runner.hpp"

namespace gpfd::python {
namespace {

class PythonBatchEvaluator final : public gp::Evaluator {
 public:
  PythonBatchEvaluator(nb::object evaluate, std::string configText, std::function<void()> done)
      : evaluate_(std::move(evaluate)),
        configText_(std::move(configText)),
        done_(std::move(done)) {}
  ~PythonBatchEvaluator() override {
    nb::gil_scoped_acquire gil;
    evaluate_.reset();
  }

  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override {
    nb::gil_scoped_acquire gil;
    nb::list tasks;
    for (std::size_t i = 0; i < genomes.size(); ++i) {
      const std::string blob = expr::wire::encodeGenome(*genomes[i]);
      tasks.append(nb::make_tuple(nb::bytes(blob.data(), blob.size()), seeds[i]));
    }
    const nb::object results = evaluate_(configText_, tasks);
    std::vector<double> out;
    for (nb::handle value : results) {
      out.push_back(nb::cast<double>(value));
      if (done_) done_();
    }
    if (out.size() != genomes.size()) {
      throw std::runtime_error(fmt::format(
          "the evaluator returned {} fitness values for {} genomes", out.size(), genomes.size()));
    }
    return out;
  }

 private:
  nb::object evaluate_;
  std::string configText_;
  std::function<void()> done_;
};

}  // namespace

std::unique_ptr<gp::Evaluator> pythonBatchEvaluator(nb::object evaluate, std::string configText,
                                                    std::function<void()> done) {
  return std::make_unique<PythonBatchEvaluator>(std::move(evaluate), std::move(configText),
                                                std::move(done));
}

std::vector<double> trialFitnessGroupOf(
    const std::string& configText, const std::vector<std::pair<nb::bytes, std::uint64_t>>& tasks) {
  // Kept while in use: an environment's step may register a name, which forgets cached tasks.
  const auto owned = cachedTask(configText, run::LearningTask::Budget::Trial);
  const run::LearningTask& task = *owned;
  std::vector<expr::Genome> genomes;
  std::vector<std::uint64_t> seeds;
  for (const auto& [genome, seed] : tasks) {
    genomes.push_back(expr::wire::decodeGenome(std::string_view(genome.c_str(), genome.size()),
                                               static_cast<int>(task.stateDim())));
    seeds.push_back(seed);
  }
  nb::gil_scoped_release release;
  std::vector<double> fitness(genomes.size(), 0.0);
  playInGroup(genomes.size(), [&](std::size_t i) {
    Rng rng(seeds[i]);
    fitness[i] = run::trialFitness(task, genomes[i], rng);
  });
  return fitness;
}

}  // namespace gpfd::python
