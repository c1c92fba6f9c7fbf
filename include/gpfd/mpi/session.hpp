// mpi: the MPI environment of one gpfd process (MPI_Init_thread / MPI_Finalize), created only in
// main and only when a process manager (mpiexec, srun) started the process, so that a plain
// `gpfd ...` never touches MPI.
#pragma once

#include <string>

namespace gpfd::mpi {

class Session {
 public:
  // True when the environment shows an MPI process manager (PMI_RANK/PMI_SIZE from MPICH's
  // hydra or Slurm's PMI, PMIX_RANK, OMPI_COMM_WORLD_SIZE).
  static bool launchedByProcessManager();

  // MPI_Init_thread with MPI_THREAD_FUNNELED: gpfd's threads compute, only the main thread
  // calls MPI. Throws std::runtime_error when MPI cannot start. At most one Session at a time.
  Session(int& argc, char**& argv);
  ~Session();  // MPI_Finalize.
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

 private:
  int rank_ = 0;
  int size_ = 1;
  int workersOnNode_ = 0;
  std::string host_;
};

}  // namespace gpfd::mpi
