// mpi: the master's side of distributed fitness evaluation. MpiEvaluator farms the genomes of a
// batch out to the worker ranks (1..N-1, each in serveAsWorker) with dynamic load balancing: a
// worker holds as many tasks as it has threads, plus up to two queued while enough remain, and
// gets the next genome whenever it returns a result. Each genome's fitness depends only on (genome,
// seed, config), so the results are bit-identical to ThreadEvaluator's for any number of ranks and
// threads, and whichever worker computes them: a worker that stops answering (killed, stopped,
// cut off) is lost, and its tasks go to the others.
#pragma once

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <list>
#include <map>
#include <string>
#include <vector>

#include "gpfd/gp/evaluator.hpp"
#include "gpfd/mpi/session.hpp"

namespace gpfd::mpi {

// How long the master waits for a sign of life from a worker (a reply or a heartbeat) before it
// takes the worker as lost. Workers send a heartbeat whenever they have sent nothing for a tenth
// of it, whether they compute or wait (their MPI thread never computes).
inline constexpr std::chrono::milliseconds kDefaultWorkerTimeout{60'000};

// On the master: tells every living worker to stop when destroyed, whatever happened before (a
// finished run, an error, an interrupt), so that no worker waits forever, and waits until each
// has answered (a worker silent for the timeout is marked lost in the session, which then ends
// the job with MPI_Abort instead of waiting for it in MPI_Finalize). Create it on rank 0 before
// anything that may throw, whenever the workers run serveAsWorker.
class WorkerRelease {
 public:
  WorkerRelease(Session& session, std::chrono::milliseconds timeout)
      : session_(session), timeout_(timeout) {}
  ~WorkerRelease();
  WorkerRelease(const WorkerRelease&) = delete;
  WorkerRelease& operator=(const WorkerRelease&) = delete;

 private:
  Session& session_;
  std::chrono::milliseconds timeout_;
};

struct MpiEvaluatorOptions {
  std::chrono::milliseconds workerTimeout = kDefaultWorkerTimeout;
  std::function<void()> onEvaluated;                     // Once per fitness (progress displays).
  std::function<void(const std::string&)> onWorkerLost;  // A line: which worker, why, its tasks.
};

class MpiEvaluator final : public gp::Evaluator {
 public:
  // Sends `configText` (a resolved ExperimentConfig) to every living worker and waits until each
  // has built its learning task. `version` must equal the workers' own. Throws when a worker
  // cannot set up (InputError when its error was one), with fewer than 2 ranks, or when no
  // worker is left.
  MpiEvaluator(Session& session, const std::string& configText, const std::string& version,
               MpiEvaluatorOptions options = {});

  // Blocks until every fitness is back. A lost worker's tasks go to the living workers; when
  // none is left it throws. When a worker fails, no further task is sent, the tasks already out
  // are awaited (so that no message is left in flight), and the failure is thrown with the
  // worker's message: InputError for an input error, std::runtime_error otherwise.
  std::vector<double> evaluate(const std::vector<const expr::Genome*>& genomes,
                               const std::vector<std::uint64_t>& seeds) override;

  int workers() const;  // Living ones.

 private:
  using Clock = std::chrono::steady_clock;
  struct Worker {
    int credit = 0;  // Threads minus tasks out (negative: tasks queued there).
    Clock::time_point heard;
    std::string host;                  // From its Ready.
    std::vector<std::uint64_t> tasks;  // Task numbers out, not answered.
  };
  // A message on its way out, with the bytes MPI_Isend reads until it completes.
  struct Outgoing {
    int rank = 0;
    std::vector<char> bytes;
    MPI_Request request = MPI_REQUEST_NULL;
  };

  void post(int rank, int tag, std::vector<char> bytes);
  // Tests the sends under way: a failed one loses its worker. Sends to lost workers are kept
  // (MPI reads their bytes until they complete) but never awaited.
  void testSends();
  // Loses every living worker not heard from for the timeout.
  void loseSilent();
  // Marks `rank` lost and says so; its tasks out go to orphans_.
  void lose(int rank, const std::string& why);

  Session& session_;
  MpiEvaluatorOptions options_;
  std::map<int, Worker> workers_;  // By rank; the lost ones are removed.
  std::list<Outgoing> sending_;
  std::vector<std::uint64_t> orphans_;  // Tasks out at lost workers, to hand out again.
  std::uint64_t nextTask_ = 0;
};

}  // namespace gpfd::mpi
