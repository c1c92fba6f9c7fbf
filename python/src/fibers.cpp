// python: fibers (fibers.hpp) on makecontext/swapcontext, each stack mapped with a guard page
// below it, so that an overflow faults instead of writing over memory.
#include "fibers.hpp"

#include <sys/mman.h>
#include <ucontext.h>
#include <unistd.h>

#include <cstdint>
#include <memory>
#include <new>
#include <stdexcept>

namespace gpfd::python {
namespace {

constexpr std::size_t kStackBytes = std::size_t{8} << 20;  // As a Linux thread's default stack.

class Stack {
 public:
  Stack() : page_(static_cast<std::size_t>(sysconf(_SC_PAGESIZE))) {
    base_ = mmap(nullptr, kStackBytes + page_, PROT_READ | PROT_WRITE,
                 MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (base_ == MAP_FAILED) throw std::bad_alloc();
    if (mprotect(base_, page_, PROT_NONE) != 0) {  // The guard page.
      munmap(base_, kStackBytes + page_);
      throw std::bad_alloc();
    }
  }
  ~Stack() { munmap(base_, kStackBytes + page_); }
  Stack(const Stack&) = delete;
  Stack& operator=(const Stack&) = delete;
  void* top() const { return static_cast<char*>(base_) + page_; }

 private:
  std::size_t page_;
  void* base_;
};

struct Fiber {
  ucontext_t context{};
  Stack stack;
  bool ended = false;
  std::function<bool()> ready;  // Set while it waits.
  std::exception_ptr error;
};

struct Schedule {
  ucontext_t main{};
  std::vector<std::unique_ptr<Fiber>> fibers;
  const std::function<void(std::size_t)>* job = nullptr;
  std::size_t running = 0;
};

thread_local Schedule* schedule = nullptr;

void entry() {
  Schedule& s = *schedule;
  const std::size_t i = s.running;
  try {
    (*s.job)(i);
  } catch (...) {
    s.fibers[i]->error = std::current_exception();
  }
  s.fibers[i]->ended = true;
}  // uc_link: back to the scheduler.

}  // namespace

std::vector<std::exception_ptr> Fibers::run(std::size_t n,
                                            const std::function<void(std::size_t)>& job) {
  if (schedule != nullptr) throw std::logic_error("fibers do not nest");
  Schedule s;
  s.job = &job;
  for (std::size_t i = 0; i < n; ++i) {
    auto fiber = std::make_unique<Fiber>();
    if (getcontext(&fiber->context) != 0) throw std::runtime_error("getcontext failed");
    fiber->context.uc_stack.ss_sp = fiber->stack.top();
    fiber->context.uc_stack.ss_size = kStackBytes;
    fiber->context.uc_link = &s.main;
    makecontext(&fiber->context, entry, 0);
    s.fibers.push_back(std::move(fiber));
  }
  schedule = &s;
  for (std::size_t left = n; left > 0;) {
    bool moved = false;
    for (std::size_t i = 0; i < n; ++i) {
      Fiber& f = *s.fibers[i];
      if (f.ended || (f.ready && !f.ready())) continue;
      f.ready = nullptr;
      s.running = i;
      swapcontext(&s.main, &f.context);
      moved = true;
      if (f.ended) --left;
    }
    if (!moved && left > 0) {
      schedule = nullptr;
      throw std::logic_error("every fiber waits and none can go on");
    }
  }
  schedule = nullptr;
  std::vector<std::exception_ptr> errors;
  for (const auto& f : s.fibers) errors.push_back(f->error);
  return errors;
}

void Fibers::waitUntil(const std::function<bool()>& ready) {
  if (schedule == nullptr) throw std::logic_error("Fibers::waitUntil outside a fiber");
  if (ready()) return;
  Schedule& s = *schedule;
  const std::size_t i = s.running;
  Fiber& f = *s.fibers[i];
  f.ready = ready;
  swapcontext(&f.context, &s.main);
  s.running = i;
}

std::size_t Fibers::current() {
  if (schedule == nullptr) throw std::logic_error("Fibers::current outside a fiber");
  return schedule->running;
}

bool Fibers::inFiber() { return schedule != nullptr; }

}  // namespace gpfd::python
