// mpi: the worker ranks' side of distributed fitness evaluation.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "gpfd/mpi/session.hpp"

namespace gpfd::mpi {

// What a test worker (tests/mpi/worker/test_worker.cpp) does besides serving; gpfd passes none,
// so that the released tool has no way to inject failures.
struct WorkerTestHooks {
  // Called on the evaluating thread before the master's task number `task` is evaluated (tasks
  // are numbered from 0 in the order the master sends them, across generations, from the start
  // of the master process); what it throws is that evaluation's failure.
  std::function<void(std::uint64_t task)> beforeTask;
};

// Serves the master until it sends Stop: receives the resolved config (once per run), builds the
// LearningTask, then evaluates each genome it is sent with run::trialFitness on its own seed,
// `threads` at a time (0: this node's cores shared among the workers on it), and replies with
// the fitness or with the exception's message; sends heartbeats (mpi_evaluator.hpp). Ignores
// SIGINT: the master decides when to stop. Returns the process exit code: 0, or 1 when the
// protocol broke (the master gone), after marking the session abandoned.
int serveAsWorker(Session& session, int threads, const std::string& version,
                  const WorkerTestHooks& hooks = {});

// The thread count serveAsWorker uses for `threads` on this node.
int workerThreads(const Session& session, int threads);

}  // namespace gpfd::mpi
