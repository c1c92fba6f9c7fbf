// Snapshots (Environment::snapshot and restore, env/snapshot.hpp): a restored instance continues
// bit for bit as the original, step counts and Tetris' board, piece and generator included; bad
// words are refused with nothing changed.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/env/snapshot.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

std::vector<std::uint64_t> bitsOf(std::span<const double> values) {
  std::vector<std::uint64_t> out;
  for (const double v : values) out.push_back(std::bit_cast<std::uint64_t>(v));
  return out;
}

struct Case {
  std::string name;
  Params params;
};

class SnapshotTest : public ::testing::TestWithParam<Case> {};

// Plays `steps` random legal actions (from `actions`), resetting after an episode ends.
void play(Environment& env, Rng& actions, Rng& resets, int steps) {
  std::vector<double> action(env.actionSpace().components);
  for (int t = 0; t < steps; ++t) {
    env.sampleAction(actions, action);
    const StepResult r = env.step(action);
    if (r.terminated || r.truncated) env.reset(resets);
  }
}

TEST_P(SnapshotTest, RestoredCopyStepsBitForBitAsTheOriginal) {
  const Case& c = GetParam();
  auto original = Registry::global().make(c.name, c.params);
  Rng resets(7), actions(11);
  original->reset(resets);
  play(*original, actions, resets, 37);  // Mid-episode, step count > 0.
  const auto words = original->snapshot();
  ASSERT_FALSE(words.empty());

  auto copy = Registry::global().make(c.name, c.params);
  copy->restore(words);
  EXPECT_EQ(copy->snapshot(), words);
  EXPECT_EQ(bitsOf(copy->state()), bitsOf(original->state()));
  Rng actionsCopy = actions;
  std::vector<double> action(original->actionSpace().components);
  int ends = 0;
  for (int t = 0; t < 400; ++t) {
    original->sampleAction(actions, action);
    const StepResult a = original->step(action);
    copy->sampleAction(actionsCopy, action);
    const StepResult b = copy->step(action);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a.reward), std::bit_cast<std::uint64_t>(b.reward));
    ASSERT_EQ(a.terminated, b.terminated) << "step " << t;
    ASSERT_EQ(a.truncated, b.truncated) << "step " << t;
    ASSERT_EQ(bitsOf(original->state()), bitsOf(copy->state())) << "step " << t;
    if (a.terminated || a.truncated) {
      ++ends;
      Rng again = resets;  // Both start the next episode from the same draws.
      original->reset(resets);
      copy->reset(again);
    }
  }
  EXPECT_GT(ends, 0) << "no episode ended: the time limit was not tested";
}

INSTANTIATE_TEST_SUITE_P(
    Builtins, SnapshotTest,
    ::testing::Values(Case{"cartpole", {{"max_steps", "50"}}},
                      Case{"acrobot", {{"max_steps", "60"}, {"actions", "discrete"}}},
                      Case{"swimmer", {{"horizon", "45"}}},
                      Case{"swimmer", {{"segments", "12"}, {"horizon", "45"}}},  // No fixed size.
                      Case{"tetris", {{"max_steps", "70"}}},
                      Case{"tetris", {{"rows", "20"}, {"cols", "10"}, {"state", "bertsekas"}}}),
    [](const ::testing::TestParamInfo<Case>& param) {
      return fmt::format("{}{}", param.param.name, param.index);
    });

TEST(Snapshot, TetrisCarriesTheBoardThatTheStateVariablesDoNot) {
  Tetris original;
  Rng rng(3);
  original.reset(rng);
  play(original, rng, rng, 9);
  Tetris copy;
  copy.restore(original.snapshot());
  EXPECT_EQ(copy.board(), original.board());
  EXPECT_EQ(copy.piece(), original.piece());
  // (setState would build a canonical board from the variables and restart the step count.)
  EXPECT_EQ(copy.snapshot(), original.snapshot());
}

TEST(Snapshot, RefusesWordsOfAnotherEnvironmentOrSizeAndChangesNothing) {
  auto cartpole = Registry::global().make("cartpole");
  auto acrobot = Registry::global().make("acrobot");
  Rng rng(1);
  acrobot->reset(rng);
  const auto before = acrobot->snapshot();
  EXPECT_THROW(acrobot->restore(cartpole->snapshot()), InputError);
  auto words = before;
  words.pop_back();
  EXPECT_THROW(acrobot->restore(words), InputError);
  words = before;
  words.push_back(0);
  EXPECT_THROW(acrobot->restore(words), InputError);
  words = before;
  words.back() = static_cast<std::uint64_t>(-1);  // A negative step count.
  EXPECT_THROW(acrobot->restore(words), InputError);
  EXPECT_THROW(acrobot->restore({}), InputError);
  EXPECT_EQ(acrobot->snapshot(), before);

  auto swimmer3 = Registry::global().make("swimmer");
  auto swimmer5 = Registry::global().make("swimmer", {{"segments", "5"}});
  EXPECT_THROW(swimmer5->restore(swimmer3->snapshot()), InputError);
  Tetris small, large(TetrisConfig{20, 10});
  EXPECT_THROW(large.restore(small.snapshot()), InputError);
  try {
    large.restore(small.snapshot());
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "tetris snapshot");
  }
}

// An environment without snapshots (a plug-in's that does not override them).
class Plain final : public Environment {
 public:
  std::string name() const override { return "plain"; }
  Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  ActionSpace actionSpace() const override {
    ActionSpace space;
    space.low = {0.0};
    space.high = {1.0};
    space.names = {"a"};
    return space;
  }
  void reset(Rng&) override {}
  std::span<const double> state() const override { return state_; }
  void setState(std::span<const double>) override {}
  StepResult step(std::span<const double>) override { return {}; }

 private:
  std::vector<std::string> names_{"x"};
  std::vector<double> state_{0.0};
};

TEST(Snapshot, TheDefaultHasNone) {
  Plain plain;
  EXPECT_TRUE(plain.snapshot().empty());
  EXPECT_THROW(plain.restore(std::vector<std::uint64_t>{1, 2}), InputError);
}

TEST(Snapshot, WriterAndReaderRoundTrip) {
  Rng rng(5);
  rng.normal();  // A spare value is kept.
  const std::vector<double> values{1.5, -0.0, 1e300};
  const std::vector<std::uint64_t> nested{9, 8};
  const auto words =
      SnapshotWriter("x").integer(-3).reals(values).rng(rng).words(nested).real(2.5).take();
  SnapshotReader in("x", words);
  EXPECT_EQ(in.integer(-5, 5, "i"), -3);
  std::vector<double> back(3);
  in.reals(back);
  EXPECT_EQ(bitsOf(back), bitsOf(values));
  Rng restored;
  restored.setState(in.rng());
  EXPECT_EQ(restored.normal(), rng.normal());
  const auto inner = in.words();
  EXPECT_EQ(std::vector<std::uint64_t>(inner.begin(), inner.end()), nested);
  EXPECT_EQ(in.real(), 2.5);
  EXPECT_NO_THROW(in.finish());
  EXPECT_THROW(SnapshotReader("y", words), InputError);
}

}  // namespace
}  // namespace gpfd::env
