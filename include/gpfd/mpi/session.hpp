// mpi: the MPI environment of one gpfd process (MPI_Init_thread / MPI_Finalize), created only in
// main and only when a process manager (mpiexec, srun) started the process, so that a plain
// `gpfd ...` never touches MPI.
#pragma once

#include <string>
#include <vector>

namespace gpfd::mpi {

class Session {
 public:
  // True when the environment shows an MPI process manager (PMI_RANK/PMI_SIZE from MPICH's
  // hydra or Slurm's PMI, PMIX_RANK, OMPI_COMM_WORLD_SIZE).
  static bool launchedByProcessManager();

  // MPI_Init_thread with MPI_THREAD_FUNNELED: gpfd's threads compute, only the main thread
  // calls MPI. Throws std::runtime_error when MPI cannot start. At most one Session at a time.
  Session(int& argc, char**& argv);
  // MPI_Barrier and MPI_Finalize, unless a rank was lost or this process abandoned the job
  // (MPI_Finalize would wait for the missing ranks).
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // The live session, or nullptr when the process runs without MPI.
  static Session* current();

  int rank() const { return rank_; }  // In MPI_COMM_WORLD; 0 is the master.
  int size() const { return size_; }  // Number of processes in MPI_COMM_WORLD.
  bool isMaster() const { return rank_ == 0; }
  // Worker processes (rank > 0) on this process's node.
  int workersOnNode() const { return workersOnNode_; }
  // This node's host name (MPI_Get_processor_name), for messages.
  const std::string& host() const { return host_; }

  // On the master: `rank` no longer answers; nothing is sent to it again (MpiEvaluator,
  // WorkerRelease), and the job ends with MPI_Abort (finish()).
  void markLost(int rank);
  bool isLost(int rank) const;
  const std::vector<int>& lostRanks() const { return lost_; }
  // This process lost the master: it leaves without MPI_Finalize.
  void abandon() { abandoned_ = true; }

  // What main returns, given the command's exit code. On a master that lost workers it does not
  // return: it ends the job with MPI_Abort(MPI_COMM_WORLD, code), since every rank must reach
  // MPI_Finalize and the lost ones never will (the job's exit code is then `code`).
  int finish(int code);

 private:
  int rank_ = 0;
  int size_ = 1;
  int workersOnNode_ = 0;
  std::string host_;
  std::vector<int> lost_;
  bool abandoned_ = false;
};

}  // namespace gpfd::mpi
