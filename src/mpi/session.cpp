#include "gpfd/mpi/session.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "finalize_watchdog.hpp"

namespace gpfd::mpi {
namespace {

Session* live = nullptr;
// Created before MPI_Init (the sockets MPI opens are the ones made after it).
const FinalizeWatchdog* watchdog = nullptr;

// How long MPI_Finalize may take before the watchdog steps in; a normal one takes milliseconds.
constexpr std::chrono::milliseconds kFinalizePatience{1000};

}  // namespace

bool Session::launchedByProcessManager() {
  for (const char* name : {"PMI_RANK", "PMI_SIZE", "PMIX_RANK", "OMPI_COMM_WORLD_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

Session::Session(int& argc, char**& argv) {
  if (live != nullptr) throw std::logic_error("only one MPI session per process");
  static const FinalizeWatchdog beforeInit;
  watchdog = &beforeInit;
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    throw std::runtime_error("MPI_Init_thread failed");
  }
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw std::runtime_error("the MPI library does not support MPI_THREAD_FUNNELED");
  }
  // Errors come back as codes (checked by the callers), so that they become exceptions.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  workersOnNode_ = rank_ == 0 ? 0 : 1;
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  if (node != MPI_COMM_NULL) {
    int ranksOnNode = 1;
    MPI_Comm_size(node, &ranksOnNode);
    int masterHere = rank_ == 0 ? 1 : 0;
    int masters = 0;
    MPI_Allreduce(&masterHere, &masters, 1, MPI_INT, MPI_SUM, node);
    workersOnNode_ = ranksOnNode - masters;
    MPI_Comm_free(&node);
  }
  char name[MPI_MAX_PROCESSOR_NAME] = {};
  int length = 0;
  MPI_Get_processor_name(name, &length);
  host_.assign(name, static_cast<std::size_t>(length));
  live = this;
}

void Session::markLost(int rank) {
  if (!isLost(rank)) lost_.push_back(rank);
}

bool Session::isLost(int rank) const {
  return std::find(lost_.begin(), lost_.end(), rank) != lost_.end();
}

int Session::finish(int code) {
  if (isMaster() && !lost_.empty()) {
    std::fprintf(stderr,
                 "gpfd: ending the MPI job with MPI_Abort(%d): %zu worker(s) lost, which "
                 "MPI_Finalize would wait for\n",
                 code, lost_.size());
    std::fflush(nullptr);
    MPI_Abort(MPI_COMM_WORLD, code);
  }
  return code;
}

Session::~Session() {
  live = nullptr;
  if (abandoned_ || !lost_.empty()) return;
  // Every rank enters MPI_Finalize at once, when every message has been delivered: with UCX's
  // tcp transport, MPICH 4.0.2's MPI_Finalize waits forever when ranks reach it apart, and now
  // and then when they reach it together, which the watchdog ends (finalize_watchdog.hpp). The
  // first barrier is polled with sleeps (MPI_Barrier would spin on a core while the others
  // come); the second, which every rank reaches at once, releases them together.
  MPI_Request barrier = MPI_REQUEST_NULL;
  if (MPI_Ibarrier(MPI_COMM_WORLD, &barrier) == MPI_SUCCESS) {
    for (int done = 0; MPI_Test(&barrier, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && !done;) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  watchdog->run([] { MPI_Finalize(); }, kFinalizePatience);
}

Session* Session::current() { return live; }

}  // namespace gpfd::mpi
