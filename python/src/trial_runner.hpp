// python: batches of learning trials (validation, confirmation, assessment) on the worker
// processes of an environment stepped in Python (gpfd.discovery.evaluator.Evaluator), and what the
// workers run. A curve depends only on its features, budget and seed (and, on a vector form seeded
// as a whole, its lockstep group), so they are the curves that run::ThreadTrialRunner gives.
#pragma once

#include <memory>
#include <string>

#include "bindings.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/run/trial_runner.hpp"

namespace gpfd::python {

// A runner over `evaluator` (gpfd.discovery.evaluator.Evaluator): its `workers` and its
// run_trials(config_text, budget, [(features, seeds), ...]), which yields each task's curves in
// order. Called without the GIL; takes it.
std::shared_ptr<run::TrialRunner> pythonTrialRunner(nb::object evaluator);

// One LearningTask per config text and budget, in this process (the workers' tasks), made at its
// first use and cached (the 16 most recently used). The caller shares ownership: hold the pointer
// while using the task, which forgetCachedTasks (an environment's step may register a name) or
// an eviction may drop from the cache meanwhile.
std::shared_ptr<const run::LearningTask> cachedTask(const std::string& configText,
                                                    run::LearningTask::Budget budget);
// Drops every cached task (their users keep theirs): an environment registered from Python under
// a name already used (a second lambda: "python:<lambda>") makes its config texts mean another
// environment.
void forgetCachedTasks();

}  // namespace gpfd::python
