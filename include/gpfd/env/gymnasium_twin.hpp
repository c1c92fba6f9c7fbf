// env: twins of Gymnasium's classic-control tasks (CartPole-v1, Acrobot-v1, Pendulum-v1,
// MountainCar-v0, MountainCarContinuous-v0): the same episode as gymnasium.make(id) gives, bit
// for bit, for any seed and actions. Seeding as Gymnasium's Env.reset does (numpy_random.hpp),
// the dynamics in the operation order and NumPy types of Gymnasium's Python (numpy_scalar.hpp),
// the observation as its float32 values, and the time limit of gymnasium.make's TimeLimit. The
// state variables are the observation's, x0, x1, ... as gpfd names a Gymnasium observation.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "gpfd/env/batch.hpp"
#include "gpfd/env/environment.hpp"
#include "gpfd/env/numpy_scalar.hpp"
#include "gpfd/util/numpy_random.hpp"

namespace gpfd::env {

// The settings every twin has: which NumPy's promotion its Python would follow, and
// gymnasium.make's time limit.
struct TwinSettings {
  numpy_scalar::Promotion promotion = numpy_scalar::Promotion::Nep50;
  int maxEpisodeSteps = 0;  // 0: none.
};

// The NumPy type of a continuous action's elements: the action space's float32 (what
// action_space.sample() and gpfd's learners give), float64, or Python numbers (a list).
using ActionKind = numpy_scalar::Kind;

class GymnasiumTwin : public Environment {
 public:
  std::string name() const override { return id_; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  std::span<const double> state() const override { return observation_; }

  // gpfd's runs: reset(seed=rng() >> 1), the seed gpfd.user_env's adapter gives Gymnasium's own
  // environment, so that the twin plays the episodes that Gymnasium's would.
  void reset(Rng& rng) override;
  // Gymnasium's reset(seed=s), s an integer >= 0 as 32-bit words (least significant first).
  void resetWithSeed(std::span<const std::uint32_t> seedWords);
  // Gymnasium's reset(): the stream continues (one never seeded starts from fresh entropy).
  void resetWithoutSeed();

  // One step of gymnasium.make(id): the dynamics, then the time limit. Discrete actions: the
  // index, InputError where Gymnasium's space would refuse it. Continuous ones: elements of
  // `kind` (step() gives the action space's float32); NaN and out-of-range values do what they
  // do in Gymnasium.
  StepResult step(std::span<const double> action) override { return stepAs(action, actionKind_); }
  StepResult stepAs(std::span<const double> action, ActionKind kind);
  // step() of a twin of final type Twin (this one), whose advance is called without a virtual call
  // so that it can inline into the caller's loop (lane_copies.hpp).
  template <class Twin>
  StepResult stepFinal(std::span<const double> action);

  // Lanes of copies of this twin stepped in one loop without a virtual call per lane
  // (lane_copies.hpp): env::makeLaneByLaneBatch's form for a twin; nullptr where a twin has none.
  virtual std::unique_ptr<BatchEnvironment> makeLanes(BatchIsa /*isa*/) const { return nullptr; }
  std::vector<std::uint64_t> snapshot() const override;
  void restore(std::span<const std::uint64_t> words) override;

  const TwinSettings& settings() const { return settings_; }

 protected:
  GymnasiumTwin(std::string id, std::size_t observationSize, TwinSettings settings,
                ActionKind actionKind = ActionKind::Float32);
  // The start state drawn from the environment's stream; writes the observation.
  virtual void start(numpy::Pcg64& random) = 0;
  // One step of the unwrapped environment; writes the observation.
  virtual StepResult advance(std::span<const double> action, ActionKind kind) = 0;
  // The observation as the float32 values Gymnasium's observation holds: the twins write their
  // float64 values and this rounds them, once, through numpy_scalar::toFloat32 (a plain
  // static_cast<float> pair can be stored unrounded by GCC 12.2). Called after start, advance and
  // by setState.
  void roundObservation();
  // The action's size checked against the space (InputError naming the twin).
  void checkActionSize(std::span<const double> action, std::size_t size) const;
  numpy_scalar::Promotion promotion() const { return settings_.promotion; }

  std::vector<double> observation_;
  // What the next steps depend on beyond the stream and the time limit, for snapshots: the
  // unwrapped environment's state and one more word of the twin's own.
  std::vector<double> dynamics_;
  std::uint64_t extra_ = 0;

 private:
  // stepAs's body; Twin is GymnasiumTwin (a virtual advance) or a final twin.
  template <class Twin>
  StepResult stepWith(Twin& twin, std::span<const double> action, ActionKind kind);

  std::string id_;
  std::vector<std::string> names_;
  TwinSettings settings_;
  ActionKind actionKind_;
  std::optional<numpy::Pcg64> random_;
  int elapsed_ = 0;                 // Steps since the reset (TimeLimit's count).
  std::optional<bool> continuous_;  // Whether the action space is continuous, once asked.
};

template <class Twin>
StepResult GymnasiumTwin::stepWith(Twin& twin, std::span<const double> action, ActionKind kind) {
  StepResult result;
  if (!continuous_) continuous_ = actionSpace().continuous();  // Once: the space allocates.
  if (kind == ActionKind::Float32 && *continuous_) {
    // Elements of a float32 array: what gpfd.user_env's adapter gives Gymnasium's environment.
    std::array<double, 4> rounded{};
    checkActionSize(action, std::min(action.size(), rounded.size()));
    for (std::size_t i = 0; i < action.size(); ++i) rounded[i] = numpy_scalar::toFloat32(action[i]);
    result = twin.advance(std::span<const double>(rounded.data(), action.size()), kind);
  } else {
    result = twin.advance(action, kind);
  }
  roundObservation();
  ++elapsed_;  // TimeLimit: truncated once the episode has run its steps.
  if (settings_.maxEpisodeSteps > 0 && elapsed_ >= settings_.maxEpisodeSteps) {
    result.truncated = true;
  }
  return result;
}

template <class Twin>
StepResult GymnasiumTwin::stepFinal(std::span<const double> action) {
  return stepWith(static_cast<Twin&>(*this), action, actionKind_);
}

}  // namespace gpfd::env
