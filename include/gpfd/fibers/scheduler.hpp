// fibers: cooperative fibers on the calling thread (Boost.Context), for lockstep groups
// (python/src/lockstep_group.hpp): several jobs each play on a stack of their own and hand over
// only where they wait, so that one thread plays them all in a fixed order, without locks or a
// thread per job. A switch is a few register moves, no system call.
//
// Code that must not run on a fiber's stack (CPython checks the machine stack against its thread's
// bounds from 3.14 on) runs through onThreadStack: the calling fiber is suspended, the function
// runs on the thread's own stack, and the fiber resumes with its result or exception.
#pragma once

#include <cstddef>
#include <exception>
#include <functional>
#include <stdexcept>
#include <vector>

namespace gpfd::fibers {

// Thrown inside a job's wait when its schedule is torn down (every job waits and none can go on):
// the job unwinds, its destructors run, and the schedule ends. A job may catch it only to clean
// up: each later wait throws it again.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("the fibers' schedule was torn down") {}
};

class Scheduler {
 public:
  // job(i) for each i < n, each on a fiber of its own; returns when all have ended. Fibers run in
  // turn: one runs until it ends or waits (waitUntil), then the next ready one in index order.
  // Returns each job's exception (nullptr where it ended normally). Where every job waits and
  // none can go on, each is resumed with Cancelled and then logic_error is thrown. Fibers do not
  // nest: logic_error from within a job.
  static std::vector<std::exception_ptr> run(std::size_t n,
                                             const std::function<void(std::size_t)>& job);
  // From a job: suspends it until `ready()` is true; returns at once when it is. `ready()` is
  // called first on the job's fiber (before it suspends), then by the scheduler on the thread's
  // stack each time it looks for a fiber to resume. Outside a job: logic_error.
  static void waitUntil(const std::function<bool()>& ready);
  // Calls `f` on the thread's own stack: from a job, with the job suspended meanwhile (and no other
  // job running), f's exception rethrown in the job; outside a job, directly.
  static void onThreadStack(const std::function<void()>& f);
  // The index of the calling fiber's job; logic_error outside a job.
  static std::size_t current();
  static bool inFiber();
};

// Whether the caller runs on its thread's own stack (as the system made it), not on a fiber's.
bool onThreadsOwnStack();

}  // namespace gpfd::fibers
