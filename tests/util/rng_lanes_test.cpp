// RngLanes draws, lane by lane, exactly what standardNormal draws from the same engines: with
// AVX2 and without, for lane counts with and without a partial group, over enough draws that
// many fall outside the ziggurat's rectangles; and moving a lane moves its stream.
#include "gpfd/util/rng_lanes.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <vector>

#include "gpfd/util/cpu.hpp"
#include "gpfd/util/ziggurat.hpp"

namespace gpfd {
namespace {

TEST(RngLanes, NormalDrawsEqualTheScalarSamplerLaneByLane) {
  for (const bool avx2 : {false, true}) {
    if (avx2 && !cpuHasAvx2()) continue;
    for (const std::size_t n : {1u, 4u, 7u, 13u}) {
      RngLanes lanes(n + 2);
      std::vector<Rng> reference;
      for (std::size_t l = 0; l < n; ++l) {
        reference.emplace_back(deriveSeed(5, l));
        lanes.set(l, reference.back());
      }
      std::vector<double> out(n + 3, -99.0);
      int slow = 0;
      for (int draw = 0; draw < 3000; ++draw) {
        lanes.standardNormal(n, out.data(), avx2);
        for (std::size_t l = 0; l < n; ++l) {
          const Rng before = reference[l];
          const double want = standardNormal(reference[l]);
          Rng probe = before;
          probe();
          slow += !(probe.state().words[0] == reference[l].state().words[0]);
          ASSERT_EQ(std::bit_cast<std::uint64_t>(out[l]), std::bit_cast<std::uint64_t>(want))
              << "avx2 " << avx2 << " lanes " << n << " lane " << l << " draw " << draw;
        }
        EXPECT_EQ(out[n], -99.0);  // Nothing written beyond n.
      }
      EXPECT_GT(slow, 0) << "no draw took the slow path";
      for (std::size_t l = 0; l < n; ++l) {
        EXPECT_EQ(lanes.get(l).state().words[3], reference[l].state().words[3]);
      }
    }
  }
}

TEST(RngLanes, MovingALaneMovesItsStream) {
  RngLanes lanes(3);
  Rng a(1), b(2);
  lanes.set(0, a);
  lanes.set(2, b);
  lanes.move(2, 0);
  Rng moved = lanes.get(0);
  EXPECT_EQ(moved(), b());
}

}  // namespace
}  // namespace gpfd
