// env: the lane-by-lane batch (env::makeLaneByLaneBatch): lane l steps its own fresh copy of the
// environment through its step, one lane after another, so every lane gives what the scalar
// environment gives because it is the scalar environment. Env is the copies' type: Environment
// (a virtual step per lane) or a final type whose stepFinal<Env> steps without a virtual call, so
// that its step inlines into the loop over the lanes (a twin of a Gymnasium task:
// GymnasiumTwin::makeLanes). The `state` rows are written (after reset and step) but not read:
// lanes move only through moveLane.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "batch_driver.hpp"
#include "gpfd/env/batch.hpp"

namespace gpfd::env {

template <class Env>
class LaneCopies final : public BatchEnvironment {
 public:
  LaneCopies(std::unique_ptr<Environment> scalar, BatchIsa isa)
      : BatchEnvironment(std::move(scalar), isa),
        space_(this->scalar().actionSpace()),
        action_(space_.components, 0.0) {}

  void reset(Rng& rng, const BatchBuffers& io, std::size_t lane) override {
    Env& env = instance(lane);
    env.reset(rng);
    writeState(env, io, lane);
    io.elapsed[lane] = 0;
  }

  void step(const BatchBuffers& io) const override {
    if (!space_.continuous() && space_.components == 1) {
      batch::checkChoices(io, space_.choices.front(), scalar().name());
    }
    if (io.lanes > 0) instance(io.lanes - 1);  // Every lane stepped exists.
    for (std::size_t l = 0; l < io.lanes; ++l) {
      Env& env = *lanes_[l];
      std::span<const double> action(io.action + l, 1);  // One component: the row's element.
      if (action_.size() != 1) {
        for (std::size_t c = 0; c < action_.size(); ++c) action_[c] = io.action[c * io.stride + l];
        action = action_;
      }
      const StepResult result = stepOf(env, action);
      writeState(env, io, l);
      io.reward[l] = result.reward;
      io.terminated[l] = result.terminated ? 1 : 0;
      io.truncated[l] = result.truncated ? 1 : 0;
      ++io.elapsed[l];
    }
  }

  void moveLane(std::size_t from, std::size_t to) override {
    instance(std::max(from, to));  // Both lanes exist from here on.
    std::swap(lanes_[from], lanes_[to]);
  }

 private:
  static StepResult stepOf(Env& env, std::span<const double> action) {
    if constexpr (requires { env.template stepFinal<Env>(action); }) {
      return env.template stepFinal<Env>(action);
    } else {
      return env.step(action);
    }
  }

  // Lane `lane`'s copy (and those before it), made on first use.
  Env& instance(std::size_t lane) const {
    while (lanes_.size() <= lane) {
      auto copy = scalar().freshCopy();
      if (dynamic_cast<Env*>(copy.get()) == nullptr) {
        throw std::logic_error("lane by lane: a copy of a copy failed");
      }
      lanes_.emplace_back(static_cast<Env*>(copy.release()));
    }
    return *lanes_[lane];
  }

  static void writeState(const Env& env, const BatchBuffers& io, std::size_t lane) {
    const auto state = env.state();
    for (std::size_t i = 0; i < state.size(); ++i) io.state[i * io.stride + lane] = state[i];
  }

  ActionSpace space_;
  mutable std::vector<double> action_;               // One lane's action (several components).
  mutable std::vector<std::unique_ptr<Env>> lanes_;  // Each lane's copy.
};

// Lanes of copies of `prototype` of type Env (`isa` resolved); nullptr when it cannot be copied.
template <class Env>
std::unique_ptr<BatchEnvironment> makeLaneCopies(const Env& prototype, BatchIsa isa) {
  auto copy = prototype.freshCopy();
  if (!copy) return nullptr;
  return std::make_unique<LaneCopies<Env>>(std::move(copy), isa);
}

}  // namespace gpfd::env
