// fibers: telling AddressSanitizer about each switch of stacks (its fiber-switching interface,
// sanitizer/common_interface_defs.h), so that it checks each stack's memory and unwinds an
// exception on the right one; without AddressSanitizer these are empty. valgrind learns of the
// fibers' stacks from Boost.Context's stack allocator (BOOST_USE_VALGRIND, scheduler.cpp).
#pragma once

#include <cstddef>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#define GPFD_FIBERS_ASAN 1
#else
#define GPFD_FIBERS_ASAN 0
#endif

namespace gpfd::fibers {

struct StackBounds {
  const void* bottom = nullptr;  // The lowest address.
  std::size_t size = 0;
};

// Made just before a switch to the stack `target`; arrived() as soon as control is back on this
// stack, recording where it came from in `from` (when not null).
class SwitchToStack {
 public:
  explicit SwitchToStack([[maybe_unused]] const StackBounds& target) {
#if GPFD_FIBERS_ASAN
    __sanitizer_start_switch_fiber(&fake_, target.bottom, target.size);
#endif
  }
  void arrived([[maybe_unused]] StackBounds* from) {
#if GPFD_FIBERS_ASAN
    __sanitizer_finish_switch_fiber(fake_, from ? &from->bottom : nullptr,
                                    from ? &from->size : nullptr);
#endif
  }

 private:
  [[maybe_unused]] void* fake_ = nullptr;
};

// First thing on a new fiber's stack; records the thread's stack (where it came from).
inline void arrivedOnFiber([[maybe_unused]] StackBounds& thread) {
#if GPFD_FIBERS_ASAN
  __sanitizer_finish_switch_fiber(nullptr, &thread.bottom, &thread.size);
#endif
}

// Last thing on a fiber's stack before it ends: its fake stack can go.
inline void leavingFiberForGood([[maybe_unused]] const StackBounds& thread) {
#if GPFD_FIBERS_ASAN
  __sanitizer_start_switch_fiber(nullptr, thread.bottom, thread.size);
#endif
}

}  // namespace gpfd::fibers
