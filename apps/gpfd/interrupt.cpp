#include "interrupt.hpp"

#include <csignal>

namespace gpfd::app {
namespace {

std::atomic<bool> interrupted{false};

extern "C" void onInterrupt(int) {
  interrupted.store(true);
  std::signal(SIGINT, SIG_DFL);  // A second Ctrl-C ends the process at once.
}

}  // namespace

const std::atomic<bool>& stopOnInterrupt() {
  std::signal(SIGINT, onInterrupt);
  return interrupted;
}

}  // namespace gpfd::app
