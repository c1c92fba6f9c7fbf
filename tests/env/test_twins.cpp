// The twins of Gymnasium's classic control on their own (tests/python/test_twins.py steps them
// beside Gymnasium's): NumPy's random stream against values NumPy printed, libm's squares, the
// time limit, snapshots and bad actions.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "../../src/env/twin_params.hpp"
#include "gpfd/env/gymnasium_twin.hpp"
#include "gpfd/util/error.hpp"
#include "gpfd/util/numpy_random.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::env {
namespace {

std::unique_ptr<GymnasiumTwin> makeTwin(const std::string& id, const Params& params = {}) {
  auto made = Registry::global().make(id, params);
  auto* twin = dynamic_cast<GymnasiumTwin*>(made.get());
  EXPECT_NE(twin, nullptr) << id;
  made.release();
  return std::unique_ptr<GymnasiumTwin>(twin);
}

// Printed by NumPy 2.4: SeedSequence(s).generate_state(...) and
// Generator(PCG64(SeedSequence(s))).uniform(-0.05, 0.05) three times, then random_raw().
TEST(NumpyRandom, SeedSequenceAndPcg64GiveNumpysNumbers) {
  const numpy::SeedSequence big(numpy::SeedSequence::wordsOf(123456789012ULL));
  EXPECT_EQ(big.generateState32(4),
            (std::vector<std::uint32_t>{3600605647u, 1086553012u, 1015628100u, 4205599990u}));
  EXPECT_EQ(big.generateState64(2),
            (std::vector<std::uint64_t>{4666709655510901199ULL, 18062914418123555140ULL}));
  const std::array<std::uint32_t, 4> huge{7, 0, 0, 16};  // 2**100 + 7
  EXPECT_EQ(numpy::SeedSequence(huge).generateState32(4),
            (std::vector<std::uint32_t>{1523537530u, 7724331u, 1975607920u, 2869613165u}));

  numpy::Pcg64 zero(numpy::SeedSequence(numpy::SeedSequence::wordsOf(0)));
  EXPECT_EQ(zero.uniform(-0.05, 0.05), 0.013696168732145436);
  EXPECT_EQ(zero.uniform(-0.05, 0.05), -0.023021328623612971);
  EXPECT_EQ(zero.uniform(-0.05, 0.05), -0.045902647606380534);
  EXPECT_EQ(zero.next64(), 304881062738325533ULL);
}

TEST(Twins, LibmSquaresAreLibmsPow) {
  Rng rng(5);
  for (int i = 0; i < 400000; ++i) {
    const double x = (rng.uniform() - 0.5) * std::ldexp(1.0, static_cast<int>(rng.below(80)) - 40);
    ASSERT_EQ(twin::libmSquare(x), twin::libmPow(x, 2.0)) << x;
    const auto f = static_cast<float>(x);
    ASSERT_EQ(twin::libmSquaref(f), twin::libmPowf(f, 2.0f)) << f;
  }
  EXPECT_TRUE(std::isnan(twin::libmSquare(std::nan(""))));
  EXPECT_EQ(twin::libmSquare(0.0), 0.0);
  EXPECT_EQ(twin::libmSquare(1e300), twin::libmPow(1e300, 2.0));
}

// Where the fast paths' error bounds are thin: squares whose exact value lies within 0.05 of a
// spacing from the midpoint between fl(x * x) and its neighbour (about one square in ten).
TEST(Twins, LibmSquaresNearAMidpointAreLibmsPow) {
  Rng rng(7);
  int doubles = 0, floats = 0;
  for (int i = 0; i < 2000000 && (doubles < 40000 || floats < 40000); ++i) {
    const double x = (rng.uniform() - 0.5) * std::ldexp(1.0, static_cast<int>(rng.below(80)) - 40);
    const double product = x * x;
    if (std::fabs(twin::squareError(x, product)) > 0.45 * twin::spacingAt(product, 52)) {
      ASSERT_EQ(twin::libmSquare(x), twin::libmPow(x, 2.0)) << x;
      ++doubles;
    }
    const auto f = static_cast<float>(x);
    const double exact = static_cast<double>(f) * f;
    const double rounded = static_cast<float>(exact);
    if (std::fabs(exact - rounded) > 0.45 * twin::spacingAt(rounded, 23)) {
      ASSERT_EQ(twin::libmSquaref(f), twin::libmPowf(f, 2.0f)) << f;
      ++floats;
    }
  }
  EXPECT_GE(doubles, 40000);
  EXPECT_GE(floats, 40000);
}

TEST(Twins, ASeedGivesGymnasiumsStartAndTheTimeLimitTruncates) {
  auto cartpole = makeTwin("CartPole-v1");
  cartpole->resetWithSeed(numpy::SeedSequence::wordsOf(0));
  const auto s = cartpole->state();
  EXPECT_EQ(s[0], static_cast<float>(0.013696168732145436));
  EXPECT_EQ(s[1], static_cast<float>(-0.023021328623612971));

  auto pendulum = makeTwin("Pendulum-v1", {{"max_episode_steps", "3"}});
  pendulum->resetWithSeed(numpy::SeedSequence::wordsOf(1));
  const double torque[1] = {0.5};
  EXPECT_FALSE(pendulum->step(torque).truncated);
  EXPECT_FALSE(pendulum->step(torque).truncated);
  EXPECT_TRUE(pendulum->step(torque).truncated);
}

TEST(Twins, ASnapshotContinuesBitForBit) {
  for (const char* id :
       {"CartPole-v1", "Acrobot-v1", "Pendulum-v1", "MountainCar-v0", "MountainCarContinuous-v0"}) {
    auto a = makeTwin(id), b = makeTwin(id);
    Rng rng(3);
    a->reset(rng);
    std::vector<double> action(1, 0.0);
    const bool discrete = !a->actionSpace().continuous();
    for (int i = 0; i < 5; ++i) {
      action[0] = discrete ? 1.0 : 0.3;
      a->step(action);
    }
    b->restore(a->snapshot());
    for (int i = 0; i < 50; ++i) {
      action[0] = discrete ? static_cast<double>(i % 2) : 0.7 - 0.03 * i;
      const StepResult ra = a->step(action), rb = b->step(action);
      ASSERT_EQ(ra.reward, rb.reward) << id;
      ASSERT_EQ(std::vector<double>(a->state().begin(), a->state().end()),
                std::vector<double>(b->state().begin(), b->state().end()))
          << id;
    }
    const char* other = std::string(id) == "CartPole-v1" ? "Acrobot-v1" : "CartPole-v1";
    EXPECT_THROW(b->restore(makeTwin(other)->snapshot()), InputError) << id;
  }
}

// gpfd's learners read state() as it is, where Gymnasium's users get a float32 array: every value
// must be a float32 already (Acrobot-v1's and Pendulum-v1's were not, until the base rounded them).
TEST(Twins, TheStateGpfdReadsIsGymnasiumsFloat32Observation) {
  const auto isFloat32 = [](std::span<const double> state) {
    for (const double v : state) {
      if (static_cast<double>(static_cast<float>(v)) != v) return false;
    }
    return true;
  };
  for (const char* id :
       {"CartPole-v1", "Acrobot-v1", "Pendulum-v1", "MountainCar-v0", "MountainCarContinuous-v0"}) {
    auto twin = makeTwin(id);
    Rng rng(11);
    twin->reset(rng);
    ASSERT_TRUE(isFloat32(twin->state())) << id << " after a reset";
    std::vector<double> action(1, 0.0);
    for (int i = 0; i < 300; ++i) {
      twin->sampleAction(rng, action);
      const StepResult result = twin->step(action);
      ASSERT_TRUE(isFloat32(twin->state())) << id << " after step " << i;
      if (result.terminated || result.truncated) twin->reset(rng);
    }
    // Acrobot-v1 is set by its angles and velocities, the others by an observation.
    const std::vector<double> state =
        std::string(id) == "Acrobot-v1"
            ? std::vector<double>{0.1, -0.2, 0.3, 0.4}
            : std::vector<double>(twin->state().begin(), twin->state().end());
    twin->setState(state);
    EXPECT_TRUE(isFloat32(twin->state())) << id << " after setState";
  }
}

TEST(Twins, ADiscreteActionOutsideTheSpaceIsAnInputErrorNamingTheTask) {
  auto cartpole = makeTwin("CartPole-v1");
  Rng rng(1);
  cartpole->reset(rng);
  const double bad[1] = {2.0};
  try {
    cartpole->step(bad);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("CartPole-v1"), std::string::npos) << e.what();
  }
  const double two[2] = {0.0, 1.0};
  EXPECT_THROW(cartpole->step(two), InputError);
  EXPECT_THROW(makeTwin("CartPole-v1", {{"numpy", "3"}}), InputError);
}

}  // namespace
}  // namespace gpfd::env
