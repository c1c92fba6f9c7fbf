// mpi: the worker ranks' side of distributed fitness evaluation.
#pragma once

#include <string>

#include "gpfd/mpi/session.hpp"

namespace gpfd::mpi {

// Serves the master until it sends Stop: receives the resolved config (once per run), builds the
// LearningTask, then evaluates each genome it is sent with run::trialFitness on its own seed,
// `threads` at a time (0: this node's cores shared among the workers on it), and replies with
// the fitness or with the exception's message. Ignores SIGINT: the master decides when to stop.
// Returns the process exit code (0).
//
// Failure injection for tests: with GPFD_MPI_INJECT_FAILURE=K in its environment, a worker
// throws instead of evaluating the master's task number K (tasks are numbered from 0 in the
// order the master sends them, across generations, from the start of the master process).
int serveAsWorker(const Session& session, int threads, const std::string& version);

// The thread count serveAsWorker uses for `threads` on this node.
int workerThreads(const Session& session, int threads);

}  // namespace gpfd::mpi
