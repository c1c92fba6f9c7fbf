// python: GP's fitness evaluations of an environment stepped in Python, on the worker processes of
// a Python executor (gpfd.discovery.evaluator.Evaluator): the evaluator that the service layer
// calls for each generation, and the task each worker runs (_core.trial_fitness_group).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "gpfd/gp/evaluator.hpp"

namespace gpfd::python {

// Fitness evaluation by a Python callable, evaluate(config_text, [(genome record, seed), ...]) ->
// [fitness, ...], which runs run::trialFitness in worker processes: for environments stepped in
// Python, where threads would queue on the GIL. Same results as ThreadEvaluator, since each
// genome's fitness depends on its own seed only. `done` is called once per fitness returned.
// Call with the GIL held.
std::unique_ptr<gp::Evaluator> pythonBatchEvaluator(nb::object evaluate, std::string configText,
                                                    std::function<void()> done);

// run::trialFitness of each genome (a gpfd/expr/wire.hpp record) with Rng(seed), all in one
// lockstep group (lockstep_group.hpp): the worker processes' task (a group of one where there is no
// vector form).
std::vector<double> trialFitnessGroupOf(
    const std::string& configText, const std::vector<std::pair<nb::bytes, std::uint64_t>>& tasks);

}  // namespace gpfd::python
