// fibers: the scheduler (fibers/scheduler.hpp) on Boost.Context's fibers (fcontext: a switch saves
// and restores a few registers in user space), each stack mapped with a guard page below it, so
// that an overflow faults instead of writing over memory. Every switch goes through resumeFiber
// (thread -> fiber) or handOver (fiber -> thread), which tell AddressSanitizer and valgrind about
// the stack they move to.
#include "gpfd/fibers/scheduler.hpp"

#include <pthread.h>

// valgrind learns of each fiber's stack from the allocator (VALGRIND_STACK_REGISTER).
#if __has_include(<valgrind/valgrind.h>)
#define BOOST_USE_VALGRIND 1
#endif
#include <boost/context/fiber.hpp>
#include <boost/context/protected_fixedsize_stack.hpp>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "stack_annotations.hpp"

namespace gpfd::fibers {
namespace {

namespace ctx = boost::context;

constexpr std::size_t kStackBytes = std::size_t{8} << 20;  // As a Linux thread's default stack.
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

struct Fiber {
  ctx::fiber self;       // Where the thread resumes it (empty once it has ended).
  ctx::fiber scheduler;  // Inside it: where it hands over to the thread.
  StackBounds stack;     // Its own stack, for the sanitizers.
  bool ended = false;
  std::function<bool()> ready;                     // Set while it waits.
  const std::function<void()>* request = nullptr;  // Set while it asks for onThreadStack.
  std::exception_ptr requestError, error;
};

struct Schedule {
  std::vector<std::unique_ptr<Fiber>> fibers;
  std::size_t running = kNone;  // The job running, on its fiber or through onThreadStack.
  bool onFiberStack = false;    // Whether the code running is on a fiber's stack.
  bool cancelling = false;
  StackBounds thread;  // The thread's stack, for the sanitizers.
};

thread_local Schedule* schedule = nullptr;

// A Boost.Context stack allocator: protected_fixedsize_stack's (the guard page), recording the
// stack's bounds.
class RecordedStack {
 public:
  explicit RecordedStack(StackBounds& bounds) : bounds_(&bounds) {}
  ctx::stack_context allocate() {
    ctx::stack_context s = inner_.allocate();
    *bounds_ = {static_cast<char*>(s.sp) - s.size, s.size};
    return s;
  }
  void deallocate(ctx::stack_context& s) noexcept { inner_.deallocate(s); }

 private:
  ctx::protected_fixedsize_stack inner_{kStackBytes};
  StackBounds* bounds_;
};

// From the thread's stack into fiber i, until it hands over or ends; serves its onThreadStack
// requests on the way, here on the thread's stack.
void resumeFiber(Schedule& s, std::size_t i) {
  Fiber& f = *s.fibers[i];
  s.running = i;
  for (;;) {
    s.onFiberStack = true;
    SwitchToStack to(f.stack);
    f.self = std::move(f.self).resume();
    to.arrived(nullptr);
    s.onFiberStack = false;
    if (f.request == nullptr) break;
    try {
      (*f.request)();
    } catch (...) {
      f.requestError = std::current_exception();
    }
    f.request = nullptr;
  }
  s.running = kNone;
}

// From the running fiber to the thread's stack, until the thread resumes it.
void handOver(Schedule& s, Fiber& f) {
  SwitchToStack to(s.thread);
  f.scheduler = std::move(f.scheduler).resume();
  to.arrived(nullptr);
}

Fiber& runningFiber(const char* what) {
  if (schedule == nullptr || schedule->running == kNone) {
    throw std::logic_error(std::string("fibers::Scheduler::") + what + " outside a fiber");
  }
  if (!schedule->onFiberStack) {
    throw std::logic_error(std::string("fibers::Scheduler::") + what +
                           " from the thread's stack (within onThreadStack)");
  }
  return *schedule->fibers[schedule->running];
}

}  // namespace

std::vector<std::exception_ptr> Scheduler::run(std::size_t n,
                                               const std::function<void(std::size_t)>& job) {
  if (schedule != nullptr) throw std::logic_error("fibers do not nest");
  Schedule s;
  for (std::size_t i = 0; i < n; ++i) {
    auto fiber = std::make_unique<Fiber>();
    Fiber* f = fiber.get();
    f->self =
        ctx::fiber(std::allocator_arg, RecordedStack(f->stack), [f, i, &job](ctx::fiber&& thread) {
          arrivedOnFiber(schedule->thread);
          f->scheduler = std::move(thread);
          try {
            job(i);
          } catch (const ctx::detail::forced_unwind&) {
            throw;  // Boost.Context's own unwinding of a fiber destroyed early.
          } catch (...) {
            f->error = std::current_exception();
          }
          f->ended = true;
          leavingFiberForGood(schedule->thread);
          return std::move(f->scheduler);
        });
    s.fibers.push_back(std::move(fiber));
  }
  schedule = &s;
  const struct Reset {
    ~Reset() { schedule = nullptr; }
  } reset;
  bool deadlocked = false;
  for (std::size_t left = n; left > 0;) {
    bool moved = false;
    for (std::size_t i = 0; i < n; ++i) {
      Fiber& f = *s.fibers[i];
      if (f.ended || (f.ready && !s.cancelling && !f.ready())) continue;
      f.ready = nullptr;
      resumeFiber(s, i);
      moved = true;
      if (f.ended) --left;
    }
    if (!moved && left > 0) deadlocked = s.cancelling = true;  // Each wait now throws Cancelled.
  }
  if (deadlocked) throw std::logic_error("every fiber waits and none can go on");
  std::vector<std::exception_ptr> errors;
  for (const auto& f : s.fibers) errors.push_back(f->error);
  return errors;
}

void Scheduler::waitUntil(const std::function<bool()>& ready) {
  Fiber& f = runningFiber("waitUntil");
  Schedule& s = *schedule;
  if (s.cancelling) throw Cancelled();
  if (ready()) return;
  f.ready = ready;
  const std::size_t i = s.running;
  handOver(s, f);
  s.running = i;
  if (s.cancelling) throw Cancelled();
}

void Scheduler::onThreadStack(const std::function<void()>& f) {
  if (schedule == nullptr || !schedule->onFiberStack) {
    f();
    return;
  }
  Fiber& fiber = runningFiber("onThreadStack");
  fiber.request = &f;
  handOver(*schedule, fiber);
  if (fiber.requestError) std::rethrow_exception(std::exchange(fiber.requestError, nullptr));
}

std::size_t Scheduler::current() {
  if (schedule == nullptr || schedule->running == kNone) {
    throw std::logic_error("fibers::Scheduler::current outside a fiber");
  }
  return schedule->running;
}

bool Scheduler::inFiber() { return schedule != nullptr && schedule->running != kNone; }

bool onThreadsOwnStack() {
  pthread_attr_t attr;
  if (pthread_getattr_np(pthread_self(), &attr) != 0) return false;
  void* low = nullptr;
  std::size_t size = 0;
  const bool known = pthread_attr_getstack(&attr, &low, &size) == 0;
  pthread_attr_destroy(&attr);
  // The frame's address, not a local's: AddressSanitizer may keep locals on a heap "fake stack".
  const auto* here = static_cast<const char*>(__builtin_frame_address(0));
  return known && here >= static_cast<const char*>(low) &&
         here < static_cast<const char*>(low) + size;
}

}  // namespace gpfd::fibers
