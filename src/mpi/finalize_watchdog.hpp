// mpi (private): a way out of an MPI_Finalize that never returns.
//
// MPICH 4.0.2's UCX netmod closes every connection in MPI_Finalize and then waits in a PMI
// barrier, where it makes no progress. Over UCX's tcp transport (UCX 1.13), closing a
// connection that has carried a message since it was last flushed sends a flush request that
// the peer must answer while it makes progress. A rank that has closed all its connections sits
// in the barrier; a peer whose flush request reaches it only then waits for the answer forever,
// and the first rank waits for that peer in the barrier (MPICH removed the barrier later:
// pmodels/mpich#6596). It happens when ranks reach MPI_Finalize at different times, and now and
// then when they reach it together.
//
// The watchdog shuts down the TCP connections that MPI opened (those not open before MPI_Init,
// listening sockets left alone) of a process whose MPI_Finalize has not returned after a
// while: the peer's flush then fails at once, it leaves for the barrier, and both finish. By
// then every message of the run has been delivered (a barrier precedes MPI_Finalize).
#pragma once

#include <chrono>
#include <functional>
#include <set>

namespace gpfd::mpi {

class FinalizeWatchdog {
 public:
  // Records the sockets open now: create it before MPI_Init.
  FinalizeWatchdog();

  // Runs `finalize` (MPI_Finalize); once it has run for `patience` without returning, shuts
  // down the TCP connections opened since construction. Returns when `finalize` returns.
  void run(const std::function<void()>& finalize, std::chrono::milliseconds patience) const;

 private:
  std::set<int> before_;
};

}  // namespace gpfd::mpi
