// bench: timing two paths of the same work side by side in one process, by this thread's CPU time
// (so that the other core's load does not count).
#pragma once

#include <cstdint>
#include <ctime>

namespace gpfd::bench {

inline double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Accumulates the time and the work (steps, evaluations, ...) of one path.
struct Path {
  double seconds = 0.0;
  std::int64_t units = 0;

  // Times run(), which returns the units of work it did.
  template <class Run>
  void time(Run&& run) {
    const double start = threadSeconds();
    units += run();
    seconds += threadSeconds() - start;
  }
  double nsPerUnit() const { return units > 0 ? 1e9 * seconds / static_cast<double>(units) : 0.0; }
};

}  // namespace gpfd::bench
