#include "env_batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gpfd/env/batch.hpp"
#include "gpfd/env/tetris.hpp"
#include "gpfd/env/tetromino.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::python {
namespace {

const env::Tetris& asTetris(const env::Environment& e) {
  const auto* tetris = dynamic_cast<const env::Tetris*>(&e);
  if (tetris == nullptr) throw InputError("not a Tetris environment", e.name());
  return *tetris;
}

bool isWholeNumber(double v) { return std::isfinite(v) && v == std::floor(v); }

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
  if (dynamic_cast<const env::Tetris*>(&first) != nullptr) {
    kind_ = ActionKind::Tetris;
  } else if (space_.continuous()) {
    kind_ = ActionKind::Continuous;
  } else if (space_.components == 1) {
    kind_ = ActionKind::Discrete;
  } else {
    throw InputError(
        fmt::format("{} has a discrete action of {} components, which gpfd's Gymnasium "
                    "environments cannot drive",
                    name, space_.components),
        name);
  }
  action_.assign(space_.components, 0.0);
  auto batch = engine == Engine::Loop ? nullptr : env::makeBatchEnvironment(first);
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

void EnvBatch::checkAction(std::size_t i, const double* action) const {
  const auto where = [i] { return fmt::format("action of environment {}", i); };
  switch (kind_) {
    case ActionKind::Discrete:
      if (!isWholeNumber(action[0]) || action[0] < 0 || action[0] >= space_.choices) {
        throw InputError(fmt::format("a discrete action is an integer in 0..{}, got {}",
                                     space_.choices - 1, action[0]),
                         where());
      }
      break;
    case ActionKind::Tetris:
      for (std::size_t c = 0; c < 2; ++c) {
        if (!isWholeNumber(action[c]) || action[c] < 0) {
          throw InputError(
              fmt::format("Tetris actions are (orientation, column), non-negative integers; got "
                          "({}, {})",
                          action[0], action[1]),
              where());
        }
      }
      break;
    case ActionKind::Continuous:
      break;  // NaN counts as 0 and the environment clips to the bounds.
  }
}

env::StepResult EnvBatch::stepInstance(std::size_t i, const double* action) {
  if (lanes_) return lanes_->result(i);  // Stepped with every lane before.
  if (kind_ == ActionKind::Tetris) {
    legalTetrisAction(*envs_[i], action, action_.data());
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
      out.finalMask[i] = true;
      resetInstance(i);
    }
    ended_[i] = ended ? 1 : 0;
    writeState(i, row);
  }
}

void legalTetrisAction(const env::Environment& e, const double* action, double* legal) {
  const env::Tetris& tetris = asTetris(e);
  const auto orientations = env::orientationsOf(tetris.piece());
  const auto count = static_cast<double>(orientations.size());
  const double orientation = std::fmod(action[0], count);
  const int width = orientations[static_cast<std::size_t>(orientation)].width;
  legal[0] = orientation;
  legal[1] = std::min(action[1], static_cast<double>(tetris.config().cols - width));
}

std::vector<char> tetrisActionMask(const env::Environment& e) {
  const env::Tetris& tetris = asTetris(e);
  const int cols = tetris.config().cols;
  std::vector<char> mask(static_cast<std::size_t>(4 * cols), 0);
  const auto orientations = env::orientationsOf(tetris.piece());
  for (std::size_t o = 0; o < orientations.size(); ++o) {
    for (int c = 0; c + orientations[o].width <= cols; ++c) {
      mask[o * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c)] = 1;
    }
  }
  return mask;
}

}  // namespace gpfd::python
