// jit: gpfd's sin and cos (expr/trig.hpp) on 4 doubles at once with AVX2, for the batch kernel.
// Bit-identical to expr::trig::sin / cos lane by lane. Call only where the CPU has AVX2.
#pragma once

namespace gpfd::jit {

void sin4Avx2(double* x);  // x[0..4) = sin(x[0..4)), in place.
void cos4Avx2(double* x);

}  // namespace gpfd::jit
