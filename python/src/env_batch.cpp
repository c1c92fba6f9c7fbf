#include "env_batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gpfd/env/batch.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

bool isWholeNumber(double v) { return std::isfinite(v) && v == std::floor(v); }

// Component c's name in messages (a plug-in may leave the names out).
std::string componentName(const env::ActionSpace& space, std::size_t c) {
  return c < space.names.size() ? space.names[c] : fmt::format("action component {}", c);
}

}  // namespace

Autoreset parseAutoreset(const std::string& name) {
  if (name == "next_step" || name == "NextStep") return Autoreset::NextStep;
  if (name == "same_step" || name == "SameStep") return Autoreset::SameStep;
  if (name == "disabled" || name == "Disabled") return Autoreset::Disabled;
  throw InputError("unknown autoreset mode '" + name + "' (next_step, same_step, disabled)",
                   "autoreset_mode");
}

Engine parseEngine(const std::string& name) {
  if (name == "auto") return Engine::Auto;
  if (name == "loop") return Engine::Loop;
  if (name == "batched") return Engine::Batched;
  throw InputError("unknown engine '" + name + "' (auto, loop, batched)", "engine");
}

EnvBatch::EnvBatch(const std::string& name, const Params& params, std::size_t n,
                   Autoreset autoreset, Engine engine)
    : rngs_(n), ended_(n, 0), autoreset_(autoreset) {
  if (n == 0) throw InputError("a batch needs at least one environment", "num_envs");
  envs_.push_back(env::Registry::global().make(name, params));
  const env::Environment& first = *envs_.front();
  dim_ = first.stateDim();
  space_ = first.actionSpace();
  if (!space_.continuous() && space_.choices.size() != space_.components) {
    throw InputError(fmt::format("{}'s discrete action has {} components but {} choice counts",
                                 name, space_.components, space_.choices.size()),
                     name + " action space");
  }
  stateDependent_ = !space_.continuous() && first.hasStateDependentActions();
  maskSize_ = space_.continuous() ? 0 : space_.discreteActions();
  action_.assign(space_.components, 0.0);
  auto batch = engine == Engine::Loop ? nullptr : env::makeBatchEnvironment(first);
  if (batch && stateDependent_) {  // The legal actions are asked of each instance.
    if (engine == Engine::Batched) {
      throw InputError(name + "'s legal actions depend on the state: it steps on the loop engine",
                       "engine");
    }
    batch.reset();
  }
  if (batch) {
    // Every lane starts where a freshly made instance does (its state before any reset).
    lanes_ = std::make_unique<BatchLanes>(std::move(batch), n, first.state());
    return;
  }
  if (engine == Engine::Batched) throw InputError(name + " has no batched form", "engine");
  envs_.reserve(n);
  for (std::size_t i = 1; i < n; ++i) envs_.push_back(env::Registry::global().make(name, params));
}

const env::Environment* EnvBatch::scalarInstance(std::size_t i) const {
  if (i >= size()) throw std::out_of_range(fmt::format("no environment {} in {}", i, size()));
  return lanes_ ? nullptr : envs_[i].get();
}

void EnvBatch::state(std::size_t i, double* out) const {
  if (i >= size()) throw std::out_of_range(fmt::format("no environment {} in {}", i, size()));
  writeState(i, out);
}

void EnvBatch::setState(std::size_t i, std::span<const double> values) {
  if (i >= size()) throw std::out_of_range(fmt::format("no environment {} in {}", i, size()));
  if (!lanes_) {
    envs_[i]->setState(values);
    return;
  }
  envs_.front()->setState(values);  // The environment's own checks; the prototype has no episode.
  lanes_->writeState(i, values);
}

void EnvBatch::writeState(std::size_t i, double* row) const {
  if (lanes_) {
    lanes_->readState(i, row);
    return;
  }
  const auto state = envs_[i]->state();
  std::copy(state.begin(), state.end(), row);
}

void EnvBatch::resetInstance(std::size_t i) {
  if (lanes_) {
    lanes_->reset(i, rngs_[i]);
  } else {
    envs_[i]->reset(rngs_[i]);
  }
  ended_[i] = 0;
}

void EnvBatch::reset(const bool* mask, double* obs) {
  for (std::size_t i = 0; i < size(); ++i) {
    if (mask == nullptr || mask[i]) resetInstance(i);
    writeState(i, obs + i * dim_);
  }
}

void EnvBatch::legalActions(std::size_t i, bool* out) const {
  if (i >= size()) throw std::out_of_range(fmt::format("no environment {} in {}", i, size()));
  if (space_.continuous()) {
    throw InputError(
        prototype().name() + " has continuous actions: every value in the box is legal",
        "action_mask");
  }
  std::vector<std::uint8_t> mask(maskSize_, 1);
  if (stateDependent_) envs_[i]->legalActionMask(mask);
  std::copy(mask.begin(), mask.end(), out);
}

void EnvBatch::checkAction(std::size_t i, const double* action) const {
  const auto where = [i] { return fmt::format("action of environment {}", i); };
  for (std::size_t c = 0; c < space_.components; ++c) {
    const double a = action[c];
    if (space_.continuous()) {
      if (std::isnan(a)) {
        throw InputError(fmt::format("{} is NaN; an action is a number", componentName(space_, c)),
                         where());
      }
      continue;
    }
    const int choices = space_.choices[c];
    if (!isWholeNumber(a) || a < 0) {
      throw InputError(
          fmt::format("{} is a non-negative integer, got {}", componentName(space_, c), a),
          where());
    }
    // Where the legal actions depend on the state, the environment maps any to a legal one.
    if (!stateDependent_ && a >= choices) {
      throw InputError(fmt::format("{} is an integer in 0..{}, got {}", componentName(space_, c),
                                   choices - 1, a),
                       where());
    }
  }
}

env::StepResult EnvBatch::stepInstance(std::size_t i, const double* action) {
  if (lanes_) return lanes_->result(i);  // Stepped with every lane before.
  if (stateDependent_) {
    envs_[i]->nearestLegalAction(std::span<const double>(action, space_.components), action_);
    action = action_.data();
  }
  return envs_[i]->step(std::span<const double>(action, space_.components));
}

void EnvBatch::step(const double* actions, const BatchStep& out) {
  if (autoreset_ == Autoreset::SameStep && (out.finalObs == nullptr || out.finalMask == nullptr)) {
    throw std::logic_error("EnvBatch::step: same-step autoreset needs finalObs and finalMask");
  }
  const std::size_t components = space_.components;
  for (std::size_t i = 0; i < size(); ++i) checkAction(i, actions + i * components);
  // The batched path steps every lane at once, those that the next-step autoreset resets below
  // too (their new episode overwrites the step).
  if (lanes_) lanes_->step(actions);
  for (std::size_t i = 0; i < size(); ++i) {
    double* row = out.obs + i * dim_;
    if (out.finalMask != nullptr) out.finalMask[i] = false;
    if (autoreset_ == Autoreset::NextStep && ended_[i]) {
      resetInstance(i);
      writeState(i, row);
      out.rewards[i] = 0.0;
      out.terminated[i] = false;
      out.truncated[i] = false;
      continue;
    }
    const env::StepResult result = stepInstance(i, actions + i * components);
    out.rewards[i] = result.reward;
    out.terminated[i] = result.terminated;
    out.truncated[i] = result.truncated;
    const bool ended = result.terminated || result.truncated;
    if (ended && autoreset_ == Autoreset::SameStep) {
      writeState(i, out.finalObs + i * dim_);
      if (out.finalLegal != nullptr) legalActions(i, out.finalLegal + i * maskSize_);
      out.finalMask[i] = true;
      resetInstance(i);
    }
    ended_[i] = ended ? 1 : 0;
    writeState(i, row);
  }
}

}  // namespace gpfd::python
