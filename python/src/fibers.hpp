// python: cooperative fibers on the calling thread (POSIX ucontext): the members of a lockstep
// group (lockstep_group.hpp) each play on a stack of their own and hand over only where they wait
// for a round of the shared vector environment, so that one thread plays them all, in a fixed
// order, without locks or the scheduler's wake-ups of a thread per member at every step (a switch
// is a swapcontext: a system call for the signal mask, a few microseconds).
#pragma once

#include <cstddef>
#include <exception>
#include <functional>
#include <vector>

namespace gpfd::python {

class Fibers {
 public:
  // job(i) for each i < n, each on a fiber of its own; returns when all have ended. Fibers run in
  // turn: one runs until it ends or waits (waitUntil), then the next ready one in index order.
  // Returns each job's exception (nullptr where it ended normally).
  static std::vector<std::exception_ptr> run(std::size_t n,
                                             const std::function<void(std::size_t)>& job);
  // From a job: hands over until `ready()` is true (at once when it is). logic_error outside a job.
  static void waitUntil(const std::function<bool()>& ready);
  // The index of the calling fiber's job; logic_error outside a job.
  static std::size_t current();
  static bool inFiber();
};

}  // namespace gpfd::python
