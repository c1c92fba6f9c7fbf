// Batched environments against the scalar ones, bit for bit: single steps from random states and
// actions (wide ranges: wrapped angles, clipped velocities and actions, NaN actions, arguments
// beyond the lane sine's range), and whole trajectories with resets and time limits; every lane
// count of a partial group; the AVX2 and the one-lane-at-a-time paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "gpfd/env/batch.hpp"
#include "gpfd/env/swimmer.hpp"
#include "gpfd/util/cpu.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

struct Case {
  std::string env;
  Params params;
};

std::vector<Case> cases() {
  std::vector<Case> out{
      {"cartpole", {}},
      {"cartpole", {{"actions", "discrete"}, {"max_steps", "7"}}},
      {"cartpole", {{"gravity", "9.81"}, {"integrator", "rk4"}, {"substeps", "10"}}},
      {"acrobot", {}},
      {"acrobot", {{"dynamics", "nips"}, {"max_steps", "9"}}},
      {"acrobot", {{"integrator", "euler"}, {"substeps", "4"}, {"actions", "discrete"}}},
  };
  for (int n = 2; n <= kSwimmerFixedMaxSegments; ++n) {
    out.push_back({"swimmer", {{"segments", std::to_string(n)}, {"horizon", "6"}}});
  }
  out.push_back({"swimmer", {{"segments", "3"}, {"integrator", "rk4"}, {"substeps", "2"}}});
  return out;
}

std::string describe(const Case& c) {
  std::string text = c.env;
  for (const auto& [k, v] : c.params) text += " " + k + "=" + v;
  return text;
}

std::vector<BatchIsa> isas() {
  std::vector<BatchIsa> out{BatchIsa::Scalar};
  if (cpuHasAvx2()) out.push_back(BatchIsa::Avx2);
  if (cpuHasAvx512()) out.push_back(BatchIsa::Avx512);
  return out;
}

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) ||
         (std::isnan(a) && std::isnan(b));
}

// A batch of `lanes` lanes with a stride larger than needed (rows must not touch each other), the
// outputs filled with values that no step writes.
struct Lanes : BatchStorage {
  Lanes(std::size_t lanes, std::size_t stateDim, std::size_t components)
      : BatchStorage(lanes, lanes + 3, stateDim, components), stride(lanes + 3), io(buffers()) {
    std::fill(reward.begin(), reward.end(), -7.0);
    std::fill(terminated.begin(), terminated.end(), 9);
    std::fill(truncated.begin(), truncated.end(), 9);
  }
  std::size_t stride;
  BatchBuffers& io;
};

// A random action component: mostly legal, sometimes out of bounds or NaN (continuous).
double randomComponent(const ActionSpace& space, std::size_t c, Rng& rng) {
  if (!space.continuous()) return static_cast<double>(rng.below(space.choices.front()));
  const double r = rng.uniform();
  if (r < 0.05) return std::numeric_limits<double>::quiet_NaN();
  if (r < 0.15) return rng.uniform(-50.0, 50.0);
  return rng.uniform(space.low[c], space.high[c]);
}

// A state with wide values: angles up to many turns (and a few beyond the lane sine's 1e6
// bound), velocities beyond the clip bounds.
double randomVariable(const std::string& name, Rng& rng) {
  const bool angle = name.rfind("th", 0) == 0;
  const double r = rng.uniform();
  if (angle && r < 0.02) return rng.uniform(-3e6, 3e6);
  if (angle && r < 0.1) return rng.uniform(-40.0, 40.0);
  if (r < 0.5) return rng.uniform(-0.3, 0.3);
  return rng.uniform(-6.0, 6.0) * (name.rfind("dth", 0) == 0 ? 8.0 : 1.0);
}

class BatchVsScalar : public ::testing::TestWithParam<BatchIsa> {};

TEST_P(BatchVsScalar, SingleStepsFromRandomStatesMatchBitForBit) {
  Rng rng(2024);
  for (const Case& c : cases()) {
    SCOPED_TRACE(describe(c));
    const auto scalar = Registry::global().make(c.env, c.params);
    const auto batch = makeBatchEnvironment(*scalar, GetParam());
    ASSERT_NE(batch, nullptr);
    EXPECT_EQ(batch->isa(), GetParam());
    EXPECT_EQ(batch->usesAvx2(), GetParam() != BatchIsa::Scalar);
    const std::size_t dim = scalar->stateDim();
    const ActionSpace space = scalar->actionSpace();
    for (std::size_t lanes = 1; lanes <= 19; ++lanes) {
      Lanes b(lanes, dim, space.components);
      std::vector<std::vector<double>> states(lanes), actions(lanes);
      for (std::size_t l = 0; l < lanes; ++l) {
        for (std::size_t i = 0; i < dim; ++i) {
          states[l].push_back(randomVariable(scalar->stateNames()[i], rng));
          b.state[i * b.stride + l] = states[l][i];
        }
        for (std::size_t k = 0; k < space.components; ++k) {
          actions[l].push_back(randomComponent(space, k, rng));
          b.action[k * b.stride + l] = actions[l][k];
        }
      }
      // Every other batch allows the AVX2 path to use the lanes up to the next multiple of 4.
      b.io.scratchTail = lanes % 2 == 0 && b.stride >= (lanes + 3) / 4 * 4;
      batch->step(b.io);
      for (std::size_t l = 0; l < lanes; ++l) {
        scalar->setState(states[l]);
        const StepResult want = scalar->step(actions[l]);
        const auto s = scalar->state();
        for (std::size_t i = 0; i < dim; ++i) {
          ASSERT_TRUE(sameBits(b.state[i * b.stride + l], s[i]))
              << "lanes " << lanes << " lane " << l << " variable " << i << ": "
              << b.state[i * b.stride + l] << " vs " << s[i];
        }
        ASSERT_TRUE(sameBits(b.reward[l], want.reward)) << "lane " << l;
        ASSERT_EQ(b.terminated[l], want.terminated ? 1 : 0) << "lane " << l;
        ASSERT_EQ(b.truncated[l], want.truncated ? 1 : 0) << "lane " << l;
        ASSERT_EQ(b.elapsed[l], 1);
      }
      // The padding beyond the lanes is untouched, unless it was given as scratch.
      for (std::size_t i = 0; i < dim && !b.io.scratchTail; ++i) {
        for (std::size_t l = lanes; l < b.stride; ++l) ASSERT_EQ(b.state[i * b.stride + l], 0.0);
      }
    }
  }
}

// Lanes reset and stepped like separate scalar environments with their own random streams: the
// same states, rewards and flags at every step, time limits and terminal states included.
TEST_P(BatchVsScalar, TrajectoriesWithResetsMatchBitForBit) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(describe(c));
    const auto proto = Registry::global().make(c.env, c.params);
    const auto batch = makeBatchEnvironment(*proto, GetParam());
    const std::size_t lanes = 13, dim = proto->stateDim();  // 8 + 4 + 1: every group size.
    const ActionSpace space = proto->actionSpace();
    Lanes b(lanes, dim, space.components);
    std::vector<std::unique_ptr<Environment>> envs;
    std::vector<Rng> streams, batchStreams;
    for (std::size_t l = 0; l < lanes; ++l) {
      envs.push_back(Registry::global().make(c.env, c.params));
      streams.emplace_back(100 + l);
      batchStreams.emplace_back(100 + l);
      envs[l]->reset(streams[l]);
      batch->reset(batchStreams[l], b.io, l);
    }
    Rng actionRng(5);
    for (int t = 0; t < 40; ++t) {
      std::vector<std::vector<double>> actions(lanes);
      for (std::size_t l = 0; l < lanes; ++l) {
        for (std::size_t k = 0; k < space.components; ++k) {
          actions[l].push_back(randomComponent(space, k, actionRng));
          b.action[k * b.stride + l] = actions[l][k];
        }
      }
      batch->step(b.io);
      for (std::size_t l = 0; l < lanes; ++l) {
        const StepResult want = envs[l]->step(actions[l]);
        const auto s = envs[l]->state();
        for (std::size_t i = 0; i < dim; ++i) {
          ASSERT_TRUE(sameBits(b.state[i * b.stride + l], s[i])) << "step " << t << " lane " << l;
        }
        ASSERT_TRUE(sameBits(b.reward[l], want.reward));
        ASSERT_EQ(b.terminated[l], want.terminated ? 1 : 0) << "step " << t << " lane " << l;
        ASSERT_EQ(b.truncated[l], want.truncated ? 1 : 0) << "step " << t << " lane " << l;
        if (want.terminated || want.truncated) {
          envs[l]->reset(streams[l]);
          batch->reset(batchStreams[l], b.io, l);
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Isa, BatchVsScalar, ::testing::ValuesIn(isas()), [](const auto& param) {
  return std::string(param.param == BatchIsa::Avx512 ? "Avx512"
                     : param.param == BatchIsa::Avx2 ? "Avx2"
                                                     : "Scalar");
});

TEST(Batch, DiscreteActionOutsideTheChoicesIsAnInputErrorBeforeAnyLaneMoves) {
  const auto batch = makeBatchEnvironment("acrobot", {{"actions", "discrete"}});
  Lanes b(5, 4, 1);
  for (std::size_t l = 0; l < 5; ++l) b.state[l] = 0.5;
  b.action[3] = 3.0;
  EXPECT_THROW(batch->step(b.io), InputError);
  for (std::size_t l = 0; l < 5; ++l) EXPECT_EQ(b.state[l], 0.5);
  b.action[3] = 0.5;
  EXPECT_THROW(batch->step(b.io), InputError);
}

TEST(Batch, OnlyEnvironmentsWithABatchedFormHaveOne) {
  const auto tetris = Registry::global().make("tetris");
  EXPECT_EQ(makeBatchEnvironment(*tetris), nullptr);
  EXPECT_FALSE(hasBatchEnvironment(*tetris));
  EXPECT_THROW(makeBatchEnvironment("tetris", {}), InputError);
  Swimmer reference(SwimmerConfig{.segments = 4});
  EXPECT_TRUE(hasBatchEnvironment(reference));
  reference.setReferenceSolver(true);
  EXPECT_EQ(makeBatchEnvironment(reference), nullptr);
  EXPECT_FALSE(hasBatchEnvironment(reference));
  EXPECT_THROW(makeBatchEnvironment("swimmer", {{"segments", "9"}}), InputError);  // No kernel.
  EXPECT_FALSE(hasBatchEnvironment(*Registry::global().make("swimmer", {{"segments", "9"}})));
  for (const Case& c : cases()) {
    EXPECT_TRUE(hasBatchEnvironment(*Registry::global().make(c.env, c.params))) << describe(c);
  }
}

}  // namespace
}  // namespace gpfd::env
