#include "gpfd/jit/trig_avx2.hpp"

#include "gpfd/expr/trig_lanes.hpp"

namespace gpfd::jit {

// The lane version of expr/trig (expr/trig_lanes.hpp), compiled as AVX2.
GPFD_AVX2_KERNEL void sin4Avx2(double* x) { lanes::store(x, expr::trig::sin(lanes::load(x))); }
GPFD_AVX2_KERNEL void cos4Avx2(double* x) { lanes::store(x, expr::trig::cos(lanes::load(x))); }

}  // namespace gpfd::jit
