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

bool cpuHasAvx512() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  // As for AVX2, __builtin_cpu_supports also checks that the OS saves the ZMM and mask registers.
  static const bool has = [] {
    const char* off = std::getenv("GPFD_NO_AVX512");
    if (off != nullptr && std::strcmp(off, "1") == 0) return false;
    return cpuHasAvx2() && __builtin_cpu_supports("avx512f") &&
           __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
  }();
  return has;
#else
  return false;
#endif
}

}  // namespace gpfd
