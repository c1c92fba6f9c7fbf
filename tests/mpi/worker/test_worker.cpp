// A worker rank for the MPI tests (tests/mpi/long_mpi_evolve_test.cpp), started beside a master
// `gpfd evolve` in one MPI job:
//   mpiexec -n 1 gpfd evolve ... : -n 2 gpfd_test_mpi_worker [--fail-at-task K] [--version V]
//                                                              [--exit-delay-ms MS]
//                                                              [--vanish-at-task K kill|stop]
// It runs gpfd's own worker loop (mpi::serveAsWorker) on one thread, with what the released tool
// cannot do: --fail-at-task K throws instead of evaluating the master's task number K;
// --version V claims to be gpfd V (default: this build's version), which the master must refuse;
// --exit-delay-ms MS waits that long after the master's Stop before ending (MPI_Finalize);
// --vanish-at-task K kill|stop sends itself SIGKILL or SIGSTOP instead of evaluating its first
// task numbered K or more (with the tasks it holds unanswered), as a node that dies or hangs would.
#include <chrono>
#include <csignal>
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
  // Each option takes one value, --vanish-at-task two.
  for (int i = 1; i < argc;) {
    const std::string option = argv[i];
    const int words = option == "--vanish-at-task" ? 2 : 1;
    if (i + words >= argc) {
      std::fprintf(stderr, "gpfd_test_mpi_worker: %s needs %d value(s)\n", option.c_str(), words);
      return 2;
    }
    const std::string value = argv[i + 1];
    if (option == "--vanish-at-task") {
      const std::uint64_t at = std::stoull(value);
      const int signal = std::string(argv[i + 2]) == "stop" ? SIGSTOP : SIGKILL;
      hooks.beforeTask = [at, signal](std::uint64_t task) {
        if (task >= at) std::raise(signal);
      };
    } else if (option == "--version") {
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
    i += 1 + words;
  }

  const int code = mpi::serveAsWorker(session, 1, version, hooks);
  std::this_thread::sleep_for(std::chrono::milliseconds(exitDelayMs));
  return code;  // MPI_Finalize follows, in ~Session.
}
