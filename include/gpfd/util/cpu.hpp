// util: what the host CPU offers to gpfd's hand-vectorised code (batched environments, lockstep
// learners). The JIT asks asmjit instead (jit/x86_compiler.hpp); both honour GPFD_JIT_SSE2=1.
#pragma once

namespace gpfd {

// True when the environment sets GPFD_JIT_SSE2=1: gpfd then runs as on a CPU without AVX (the
// JIT emits SSE2 only, batched environments step their lanes one at a time). Tests use it to
// cover the fallback paths on an AVX2 machine.
bool sse2OnlyRequested();

// Whether functions marked GPFD_AVX2_KERNEL (util/lanes.hpp) may run: the CPU and the operating
// system support AVX2, and sse2OnlyRequested() is false. Computed once.
bool cpuHasAvx2();

// Whether functions marked GPFD_AVX512_KERNEL (util/lanes.hpp) may run: cpuHasAvx2(), and the CPU
// and the operating system support AVX-512 F, DQ and VL, and GPFD_NO_AVX512=1 is not set (to run
// the AVX2 paths on such a CPU). Computed once.
bool cpuHasAvx512();

}  // namespace gpfd
