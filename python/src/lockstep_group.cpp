// python: lockstep groups (lockstep_group.hpp).
#include "lockstep_group.hpp"

#include <exception>
#include <stdexcept>

#include "gpfd/fibers/scheduler.hpp"

namespace gpfd::python {
namespace {

thread_local LockstepGroup* currentGroup = nullptr;

}  // namespace

std::shared_ptr<VectorHub> LockstepGroup::hub(
    const std::string& name, const std::function<std::shared_ptr<VectorHub>(std::size_t)>& make) {
  if (hub_ == nullptr) {
    hub_ = make(left_.size());
    name_ = name;
    for (std::size_t m = 0; m < left_.size(); ++m) {
      if (left_[m]) hub_->leave(m);  // Nobody waits on a hub just made: no round runs.
    }
  } else if (name != name_) {
    throw std::logic_error("a lockstep group plays one environment, " + name_ + ", not " + name);
  }
  return hub_;
}

void LockstepGroup::leave(std::size_t m) {
  left_[m] = true;
  if (hub_ != nullptr) hub_->leave(m);
}

LockstepGroup* LockstepGroup::current() {
  return fibers::Scheduler::inFiber() ? currentGroup : nullptr;
}

std::size_t LockstepGroup::currentMember() { return fibers::Scheduler::current(); }

void playInGroup(std::size_t n, const std::function<void(std::size_t)>& job) {
  LockstepGroup group(n);
  struct Scope {
    explicit Scope(LockstepGroup* g) { currentGroup = g; }
    ~Scope() { currentGroup = nullptr; }
  } scope(&group);
  const std::vector<std::exception_ptr> errors = fibers::Scheduler::run(n, [&](std::size_t i) {
    std::exception_ptr error;
    try {
      job(i);
    } catch (...) {
      error = std::current_exception();
    }
    try {
      group.leave(i);
    } catch (...) {
      if (!error) error = std::current_exception();
    }
    if (error) std::rethrow_exception(error);
  });
  std::exception_ptr first;
  for (const std::exception_ptr& e : errors) {
    if (!e) continue;
    try {
      std::rethrow_exception(e);
    } catch (const LockstepGroupFailed&) {
      if (!first) first = e;
    } catch (...) {
      std::rethrow_exception(e);
    }
  }
  if (first) std::rethrow_exception(first);
}

}  // namespace gpfd::python
