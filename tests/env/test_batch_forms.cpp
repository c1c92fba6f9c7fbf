// Batched forms declared in the registry (EnvInfo::batch): makeBatchEnvironment finds them by the
// environment's name, whoever registered it; and the lane-by-lane batch (makeLaneByLaneBatch),
// which steps copies of any environment, against the scalar environment bit for bit, lane moves
// included.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpfd/env/batch.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/swimmer.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

struct CounterConfig {
  bool batched = false;
  static const ParamTable<CounterConfig>& table() {
    static const auto table = ParamTable<CounterConfig>("test-counter")
                                  .flag(
                                      "batched", [](auto& c) -> auto& { return c.batched; },
                                      "whether the instance has the batched form");
    return table;
  }
};

// A counter: x += a per step; its parameter `batched` says whether an instance has the form.
class Counter final : public Environment {
 public:
  explicit Counter(bool batched, std::string name = "test-counter")
      : batched_(batched), name_(std::move(name)) {}
  std::string name() const override { return name_; }
  Params params() const override {
    return CounterConfig::table().write(CounterConfig{.batched = batched_});
  }
  const std::vector<std::string>& stateNames() const override { return names_; }
  ActionSpace actionSpace() const override {
    ActionSpace space;
    space.low = {-1.0};
    space.high = {1.0};
    space.names = {"a"};
    return space;
  }
  void reset(Rng& rng) override { x_ = rng.uniform(); }
  std::span<const double> state() const override { return {&x_, 1}; }
  void setState(std::span<const double> s) override { x_ = s[0]; }
  StepResult step(std::span<const double> a) override {
    x_ += a[0];
    return {x_, false, false};
  }
  bool batched() const { return batched_; }

 private:
  bool batched_;
  std::string name_;
  double x_ = 0.0;
  std::vector<std::string> names_{"x"};
};

class CounterBatch final : public BatchEnvironment {
 public:
  CounterBatch(const Counter& c, BatchIsa isa)
      : BatchEnvironment(std::make_unique<Counter>(c.batched()), isa) {}
  void step(const BatchBuffers& io) const override {
    for (std::size_t l = 0; l < io.lanes; ++l) io.state[l] += io.action[l];
  }
};

std::unique_ptr<Counter> makeCounter(const Params& p) {
  return std::make_unique<Counter>(CounterConfig::table().read(p).batched);
}

// Registers "test-counter" with its batched form (once).
void registerCounter() {
  static const bool done = [] {
    EnvInfo info{"test-counter", "a counter (test)", CounterConfig::table().specs(), makeCounter};
    info.batch.available = [](const Environment& e) {
      const auto* c = dynamic_cast<const Counter*>(&e);
      return c != nullptr && c->batched();
    };
    info.batch.make = [](const Environment& e, BatchIsa isa) {
      return std::make_unique<CounterBatch>(dynamic_cast<const Counter&>(e), isa);
    };
    Registry::global().add(std::move(info));
    return true;
  }();
  static_cast<void>(done);
}

TEST(BatchForms, ARegisteredFormIsFoundThroughTheRegistry) {
  registerCounter();
  const Counter with(true), without(false);
  EXPECT_TRUE(hasBatchEnvironment(with));
  EXPECT_FALSE(hasBatchEnvironment(without));
  EXPECT_EQ(makeBatchEnvironment(without), nullptr);
  const auto batch = makeBatchEnvironment(with, BatchIsa::Scalar);
  ASSERT_NE(batch, nullptr);
  EXPECT_NE(dynamic_cast<const CounterBatch*>(batch.get()), nullptr);
  EXPECT_EQ(batch->isa(), BatchIsa::Scalar);
  EXPECT_NE(makeBatchEnvironment(with)->isa(), BatchIsa::Auto);  // Resolved before the maker.
  EXPECT_NE(makeBatchEnvironment("test-counter", {{"batched", "true"}}), nullptr);
  EXPECT_THROW(makeBatchEnvironment("test-counter", {{"batched", "false"}}), InputError);
  // An environment the registry does not know by its name has none.
  EXPECT_FALSE(hasBatchEnvironment(Counter(true, "unregistered-counter")));
}

// An environment under a built-in's name that is not the built-in has no batched form.
TEST(BatchForms, AnotherTypeUnderABuiltInNameHasNone) {
  EXPECT_TRUE(hasBatchEnvironment(CartPole{}));
  EXPECT_FALSE(hasBatchEnvironment(Counter(true, "cartpole")));
  EXPECT_EQ(makeBatchEnvironment(Counter(true, "cartpole")), nullptr);
}

TEST(BatchForms, TheRegistryRefusesAFormWithoutItsMaker) {
  Registry registry;
  EnvInfo info{"lonely", "", {}, makeCounter};
  info.batch.available = [](const Environment&) { return true; };
  EXPECT_THROW(registry.add(info), InputError);
}

// --- Lane by lane ---------------------------------------------------------------------------

struct Case {
  std::string env;
  Params params;
};

std::vector<Case> laneCases() {
  return {{"swimmer", {{"segments", "9"}, {"horizon", "7"}}},  // No batched form.
          {"cartpole", {{"actions", "discrete"}, {"max_steps", "9"}}},
          {"acrobot", {{"max_steps", "11"}}},
          {"tetris", {{"cols", "6"}, {"rows", "8"}}},  // Two-component, state-bound actions.
          // The twins of Gymnasium's tasks: their own lanes (GymnasiumTwin::makeLanes).
          {"CartPole-v1", {{"max_episode_steps", "9"}}},
          {"Acrobot-v1", {{"max_episode_steps", "11"}}},
          {"Pendulum-v1", {{"max_episode_steps", "12"}}},
          {"Pendulum-v1", {{"max_episode_steps", "12"}, {"numpy", "1"}}},
          {"MountainCar-v0", {{"max_episode_steps", "10"}}},
          {"MountainCarContinuous-v0", {{"max_episode_steps", "10"}}}};
}

// Lanes of a lane-by-lane batch and, beside them, scalar environments (one per lane, made by the
// registry) given the same resets, actions and lane moves: every step must agree bit for bit.
TEST(LaneByLane, StepsEveryLaneAsTheScalarEnvironmentDoes) {
  for (const Case& c : laneCases()) {
    SCOPED_TRACE(c.env);
    const auto prototype = Registry::global().make(c.env, c.params);
    const auto batch = makeLaneByLaneBatch(*prototype);
    ASSERT_NE(batch, nullptr);
    constexpr std::size_t kLanes = 6, kStride = 9;
    const std::size_t dim = prototype->stateDim();
    const std::size_t components = prototype->actionSpace().components;
    BatchStorage store(kLanes, kStride, dim, components);
    BatchBuffers& io = store.buffers();
    std::vector<std::unique_ptr<Environment>> scalars;
    std::vector<int> elapsed(kLanes, 0);
    Rng seeds(31);
    const auto start = [&](std::size_t l) {
      const std::uint64_t seed = seeds();
      Rng a(seed), b(seed);
      batch->reset(a, io, l);
      scalars[l]->reset(b);
      elapsed[l] = 0;
    };
    for (std::size_t l = 0; l < kLanes; ++l) {
      scalars.push_back(Registry::global().make(c.env, c.params));
      start(l);
    }
    Rng rng(5);
    std::vector<double> action(components);
    std::size_t lanes = kLanes;
    int resets = 0;
    for (int t = 0; t < 40; ++t) {
      if (t == 15 || t == 25) {  // The player's compaction: the last lane moves into lane 1.
        for (std::size_t i = 0; i < dim; ++i)
          io.state[i * kStride + 1] = io.state[i * kStride + lanes - 1];
        io.elapsed[1] = io.elapsed[lanes - 1];
        batch->moveLane(lanes - 1, 1);
        std::swap(scalars[1], scalars[lanes - 1]);
        elapsed[1] = elapsed[lanes - 1];
        io.lanes = --lanes;
      }
      for (std::size_t l = 0; l < lanes; ++l) {
        scalars[l]->sampleAction(rng, action);
        for (std::size_t k = 0; k < components; ++k) store.action[k * kStride + l] = action[k];
      }
      batch->step(io);
      for (std::size_t l = 0; l < lanes; ++l) {
        for (std::size_t k = 0; k < components; ++k) action[k] = store.action[k * kStride + l];
        const StepResult r = scalars[l]->step(action);
        ++elapsed[l];
        const auto state = scalars[l]->state();
        for (std::size_t i = 0; i < dim; ++i) {
          ASSERT_TRUE(sameBits(state[i], store.state[i * kStride + l]))
              << "step " << t << " lane " << l;
        }
        ASSERT_TRUE(sameBits(r.reward, store.reward[l]));
        ASSERT_EQ(r.terminated, store.terminated[l] == 1);
        ASSERT_EQ(r.truncated, store.truncated[l] == 1);
        ASSERT_EQ(elapsed[l], store.elapsed[l]);
        if (r.terminated || r.truncated) {
          start(l);
          ++resets;
        }
      }
    }
    EXPECT_GT(resets, 0);
  }
}

TEST(LaneByLane, ADiscreteActionOutsideTheChoicesIsAnInputErrorBeforeAnyLaneMoves) {
  const auto batch =
      makeLaneByLaneBatch(*Registry::global().make("cartpole", {{"actions", "discrete"}}));
  BatchStorage store(4, 4, 4, 1);
  Rng rng(1);
  for (std::size_t l = 0; l < 4; ++l) batch->reset(rng, store.buffers(), l);
  const std::vector<double> before = store.state;
  store.action = {1.0, 0.0, 2.0, 1.0};
  EXPECT_THROW(batch->step(store.buffers()), InputError);
  EXPECT_EQ(store.state, before);
  EXPECT_EQ(store.elapsed, std::vector<std::int32_t>(4, 0));
}

// Lane by lane needs copies: of an environment the registry knows under its name, of its type.
TEST(LaneByLane, CopiesComeFromTheRegistryOrTheEnvironment) {
  registerCounter();
  EXPECT_EQ(Counter(true, "unregistered-counter").freshCopy(), nullptr);
  EXPECT_EQ(makeLaneByLaneBatch(Counter(true, "unregistered-counter")), nullptr);
  EXPECT_EQ(Counter(false, "cartpole").freshCopy(), nullptr);  // The registry makes a CartPole.
  const auto copy = Counter(true).freshCopy();
  ASSERT_NE(copy, nullptr);
  EXPECT_TRUE(dynamic_cast<const Counter&>(*copy).batched());
  // The swimmer's reference solver is a setting beyond its parameters: its copy keeps it.
  Swimmer reference(SwimmerConfig{.segments = 4});
  reference.setReferenceSolver(true);
  EXPECT_EQ(dynamic_cast<const Swimmer&>(*reference.freshCopy()).fixedSizeBody(), nullptr);
  EXPECT_NE(dynamic_cast<const Swimmer&>(*Swimmer(SwimmerConfig{.segments = 4}).freshCopy())
                .fixedSizeBody(),
            nullptr);
}

}  // namespace
}  // namespace gpfd::env
