#include "gpfd/util/cpu.hpp"

#include <cstdlib>
#include <cstring>

namespace gpfd {

bool sse2OnlyRequested() {
  const char* value = std::getenv("GPFD_JIT_SSE2");
  return value != nullptr && std::strcmp(value, "1") == 0;
}

bool cpuHasAvx2() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  // __builtin_cpu_supports checks the CPUID bit and that the OS saves the YMM registers.
  static const bool has = !sse2OnlyRequested() && __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

}  // namespace gpfd
