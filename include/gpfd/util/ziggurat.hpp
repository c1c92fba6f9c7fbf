// util: standard normal draws by the ziggurat method (Marsaglia & Tsang 2000, "The Ziggurat Method
// for Generating Random Variables", Journal of Statistical Software 5(8)), 256 layers. Exact: a
// draw is a sample of N(0, 1) up to the 53-bit resolution of the uniforms, not an approximation.
// About 99% of draws take one engine output, one multiplication and one comparison; the rest go
// through the wedge and tail tests (exp, log). The layer index, the sign and the uniform come
// from disjoint bits of one 64-bit output (bits 0-7, bit 8, bits 11-63), so they are independent.
#pragma once

#include <cstdint>

#include "gpfd/util/rng.hpp"
#include "gpfd/util/ziggurat_tables.hpp"

namespace gpfd {
namespace ziggurat {

// The draws that fall outside the rectangles: `word` is the engine output that missed.
double slowDraw(Rng& rng, std::uint64_t word);

}  // namespace ziggurat

// One N(0, 1) draw from `rng`; the same engine state always gives the same value.
inline double standardNormal(Rng& rng) {
  const std::uint64_t word = rng();
  const unsigned layer = word & 0xffu;
  const double z = static_cast<double>(word >> 11) * 0x1.0p-53 * ziggurat::kLayerX[layer];
  if (z < ziggurat::kLayerX[layer + 1]) return (word & 0x100u) ? -z : z;
  return ziggurat::slowDraw(rng, word);
}

}  // namespace gpfd
