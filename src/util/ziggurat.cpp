#include "gpfd/util/ziggurat.hpp"

#include <cmath>

namespace gpfd::ziggurat {

double slowDraw(Rng& rng, std::uint64_t word) {
  for (;;) {
    const unsigned layer = word & 0xffu;
    const bool negative = (word & 0x100u) != 0;
    const double z = static_cast<double>(word >> 11) * 0x1.0p-53 * kLayerX[layer];
    if (z < kLayerX[layer + 1]) return negative ? -z : z;
    if (layer == 0) {
      // The tail beyond r (Marsaglia 1964): a = -log(u1) / r, b = -log(u2) until 2 b > a^2;
      // then r + a. The uniforms are taken in (0, 1].
      double a = 0.0, b = 0.0;
      do {
        a = -std::log(1.0 - rng.uniform()) / kTailStart;
        b = -std::log(1.0 - rng.uniform());
      } while (!(b + b > a * a));
      return negative ? -(kTailStart + a) : kTailStart + a;
    }
    // The wedge of layer k: a uniform height between f(X[k]) and f(X[k+1]), under f(z)?
    const double y = kLayerF[layer] + rng.uniform() * (kLayerF[layer + 1] - kLayerF[layer]);
    if (y < std::exp(-0.5 * z * z)) return negative ? -z : z;
    word = rng();
  }
}

}  // namespace gpfd::ziggurat
