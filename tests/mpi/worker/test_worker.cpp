// A worker rank for the MPI tests (tests/mpi/long_mpi_evolve_test.cpp), started beside a master
// `gpfd evolve` in one MPI job:
//   mpiexec -n 1 gpfd evolve ... : -n 2 gpfd_test_mpi_worker [--fail-at-task K] [--version V]
//                                                              [--exit-delay-ms MS]
// It runs gpfd's own worker loop (mpi::serveAsWorker) on one thread, with what the released tool
// cannot do: --fail-at-task K throws instead of evaluating the master's task number K;
// --version V claims to be gpfd V (default: this build's version), which the master must refuse;
// --exit-delay-ms MS waits that long after the master's Stop before ending (MPI_Finalize).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>

#include "gpfd/mpi/session.hpp"
#include "gpfd/mpi/worker.hpp"
#include "gpfd/version.hpp"

int main(int argc, char** argv) {
  using namespace gpfd;
  mpi::Session session(argc, argv);
  std::string version = kVersion;
  mpi::WorkerTestHooks hooks;
  int exitDelayMs = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i], value = argv[i + 1];
    if (option == "--version") {
      version = value;
    } else if (option == "--exit-delay-ms") {
      exitDelayMs = std::stoi(value);
    } else if (option == "--fail-at-task") {
      const std::uint64_t failAt = std::stoull(value);
      hooks.beforeTask = [failAt](std::uint64_t task) {
        if (task == failAt)
          throw std::runtime_error("injected failure at task " + std::to_string(task));
      };
    } else {
      std::fprintf(stderr, "gpfd_test_mpi_worker: unknown option %s\n", option.c_str());
      return 2;
    }
  }
  if (argc % 2 == 0) {
    std::fprintf(stderr, "gpfd_test_mpi_worker: options come in pairs (OPTION VALUE)\n");
    return 2;
  }
  const int code = mpi::serveAsWorker(session, 1, version, hooks);
  std::this_thread::sleep_for(std::chrono::milliseconds(exitDelayMs));
  return code;  // MPI_Finalize follows, in ~Session.
}
