#include "finalize_watchdog.hpp"

#include <sys/socket.h>

#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

namespace gpfd::mpi {
namespace {

// The process's open file descriptors.
std::set<int> openDescriptors() {
  std::set<int> fds;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", error)) {
    try {
      fds.insert(std::stoi(entry.path().filename().string()));
    } catch (const std::exception&) {
    }
  }
  return fds;
}

// A connected (not listening) TCP socket over IPv4 or IPv6.
bool isTcpConnection(int fd) {
  int domain = 0, type = 0, listening = 0;
  socklen_t size = sizeof domain;
  if (getsockopt(fd, SOL_SOCKET, SO_DOMAIN, &domain, &size) != 0) return false;
  size = sizeof type;
  if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &size) != 0) return false;
  size = sizeof listening;
  if (getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &size) != 0) return false;
  return (domain == AF_INET || domain == AF_INET6) && type == SOCK_STREAM && listening == 0;
}

}  // namespace

FinalizeWatchdog::FinalizeWatchdog() : before_(openDescriptors()) {}

void FinalizeWatchdog::run(const std::function<void()>& finalize,
                           std::chrono::milliseconds patience) const {
  std::mutex mutex;
  std::condition_variable done;
  bool finished = false;
  std::jthread watch([&] {
    std::unique_lock lock(mutex);
    if (done.wait_for(lock, patience, [&] { return finished; })) return;
    for (const int fd : openDescriptors()) {
      if (fd > 2 && !before_.contains(fd) && isTcpConnection(fd)) shutdown(fd, SHUT_RDWR);
    }
  });
  finalize();
  {
    std::lock_guard lock(mutex);
    finished = true;
  }
  done.notify_one();
}

}  // namespace gpfd::mpi
