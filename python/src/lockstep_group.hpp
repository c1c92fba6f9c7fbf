// python: a lockstep group: the fitness evaluations (or learning runs) of several feature sets
// played as fibers of one thread (gpfd/fibers/scheduler.hpp), whose lockstep players share one
// vector environment (vector_hub.hpp), so that one vector step advances the episodes of all of
// them. On gpfd.adapters.sources's vector forms stepped in Python, where a step costs mostly per
// call (NumPy, EnvPool), this is what spreads that cost over hundreds of lanes. Python itself never
// runs on a member's fiber: every call into it goes to the thread's own stack (python_call.hpp), so
// that groups play alike on every CPython (3.14 and later check the stack's bounds).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "vector_hub.hpp"

namespace gpfd::python {

class LockstepGroup {
 public:
  explicit LockstepGroup(std::size_t members) : left_(members, false) {}

  // The group's vector environment of `name`, made by `make(members)` on the first call.
  std::shared_ptr<VectorHub> hub(
      const std::string& name, const std::function<std::shared_ptr<VectorHub>(std::size_t)>& make);
  // Member `m` plays no more (its job ended, or failed); may run a round that waited only for it,
  // and throw what that round threw.
  void leave(std::size_t m);

  // The group whose member the caller plays, and which member; nullptr outside a group.
  static LockstepGroup* current();
  static std::size_t currentMember();

 private:
  std::vector<bool> left_;
  std::string name_;
  std::shared_ptr<VectorHub> hub_;
};

// job(i) for each i < n, each as member i of one lockstep group, so that the vector forms the
// jobs' lockstep players make share one vector environment. Throws the first job's error (the
// cause, not another member's LockstepGroupFailed). Called without the GIL.
void playInGroup(std::size_t n, const std::function<void(std::size_t)>& job);

}  // namespace gpfd::python
