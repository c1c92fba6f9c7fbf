// python: lets Debian's libasmjit.a, compiled as position-independent *executable* code, link into
// this shared module. Such code reads C's `stderr` with a PC-relative access that only an
// executable can resolve, and asmjit does so in one place (its debug output). The module is linked
// with -Wl,--wrap=stderr (cmake/python_module.cmake), which sends every such reference to
// __wrap_stderr below, a module-local copy of the C library's stream; __real_stderr is the C
// library's own. All other code reads stderr through the GOT and sees the same stream.
#include <cstdio>

extern "C" {
extern FILE* __real_stderr;
__attribute__((visibility("hidden"))) FILE* __wrap_stderr = nullptr;
}

namespace {

const bool kStderrBound = [] {
  __wrap_stderr = __real_stderr;
  return true;
}();

}  // namespace
