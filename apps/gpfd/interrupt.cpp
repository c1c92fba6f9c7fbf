#include "interrupt.hpp"

#include <unistd.h>

#include <csignal>
#include <cstring>

namespace gpfd::app {
namespace {

std::atomic<bool> interrupted{false};
const char* noticeText = "";

extern "C" void onInterrupt(int) {
  interrupted.store(true);
  std::signal(SIGINT, SIG_DFL);  // A second Ctrl-C ends the process at once.
  // write(2) is async-signal-safe; what it fails to write is lost, which is harmless.
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, noticeText, std::strlen(noticeText));
}

}  // namespace

const std::atomic<bool>& stopOnInterrupt(const char* notice) {
  noticeText = notice;
  std::signal(SIGINT, onInterrupt);
  return interrupted;
}

}  // namespace gpfd::app
