// python: every call into Python from the members of a lockstep group goes through withPython, so
// that Python never runs on a fiber's stack: the member is suspended, the call runs on the
// thread's own stack with the GIL held, and the member resumes with its result or exception
// (fibers::Scheduler::onThreadStack). Outside a group it is a plain call with the GIL.
#pragma once

#include <optional>
#include <type_traits>
#include <utility>

#include "bindings.hpp"
#include "gpfd/fibers/scheduler.hpp"

namespace gpfd::python {

// f() with the GIL, on the thread's stack; its result must be a C++ value (no Python object:
// that would be released without the GIL).
template <typename F>
auto withPython(F&& f) {
  using Result = std::invoke_result_t<F&>;
  if constexpr (std::is_void_v<Result>) {
    fibers::Scheduler::onThreadStack([&] {
      nb::gil_scoped_acquire gil;
      f();
    });
  } else {
    std::optional<Result> result;
    fibers::Scheduler::onThreadStack([&] {
      nb::gil_scoped_acquire gil;
      result.emplace(f());
    });
    return std::move(*result);
  }
}

}  // namespace gpfd::python
