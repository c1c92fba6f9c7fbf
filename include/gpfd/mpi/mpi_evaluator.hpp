// mpi: the master's side of distributed fitness evaluation. MpiEvaluator farms the genomes of a
// batch out to the worker ranks (1..N-1, each in serveAsWorker) with dynamic load balancing: a
// worker holds as many tasks as it has threads, plus up to two queued while enough remain, and
// gets the next genome whenever it returns a result. Each genome's fitness depends only on (genome,
// seed, config), so the results are bit-identical to ThreadEvaluator's for any number of ranks and
// threads.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gpfd/gp/evaluator.hpp"
#include "gpfd/mpi/session.hpp"

namespace gpfd::mpi {

// On the master: sends every worker the Stop message when destroyed, whatever happened before
// (a finished run, an error, an interrupt), so that no worker waits forever. Create it on rank 0
// before anything that may throw, whenever the workers run serveAsWorker.
class WorkerRelease {
 public:
  explicit WorkerRelease(const Session& session) : session_(session) {}
  ~WorkerRelease();
  WorkerRelease(const WorkerRelease&) = delete;
  WorkerRelease& operator=(const WorkerRelease&) = delete;

 private:
  const Session& session_;
};

class MpiEvaluator final : public gp::Evaluator {
 public:
  // Sends `configText` (a resolved ExperimentConfig) to every worker and waits until each has
  // built its learning task. `version` must equal the workers' own. `onEvaluated` is called once
  // per returned fitness (progress displays). Throws when a worker cannot set up (InputError
  // when its error was one), or with fewer than 2 ranks.
  MpiEvaluator(const Session& session, const std::string& configText, const std::string& version,
               std::function<void()> onEvaluated = {});

  // Blocks until every fitness is back. When a worker fails, no further task is sent, the tasks
  // already out are awaited (so that no message is left in flight), and the failure is thrown
  // with the worker's message: InputError for an input error, std::runtime_error otherwise.
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override;

  int workers() const { return static_cast<int>(credit_.size()); }
  // Tasks the workers evaluate at once, summed over the workers (their threads).
  int capacity() const;

 private:
  const Session& session_;
  std::function<void()> onEvaluated_;
  // credit_[w - 1]: worker rank w's threads minus its tasks out (negative: tasks queued there).
  std::vector<int> credit_;
  std::uint64_t nextTask_ = 0;
};

}  // namespace gpfd::mpi
