#include "env_batch.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

EnvBatch::EnvBatch(const std::string& name, const Params& params, std::size_t n,
                   Autoreset autoreset)
    : rngs_(n), ended_(n, 0), autoreset_(autoreset) {
  if (n == 0) throw InputError("a batch needs at least one environment", "num_envs");
  envs_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) envs_.push_back(env::Registry::global().make(name, params));
  dim_ = envs_.front()->stateDim();
  space_ = envs_.front()->actionSpace();
  if (dynamic_cast<const env::Tetris*>(envs_.front().get()) != nullptr) {
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
}

void EnvBatch::writeState(std::size_t i, double* row) const {
  const auto state = envs_[i]->state();
  std::copy(state.begin(), state.end(), row);
}

void EnvBatch::reset(const bool* mask, double* obs) {
  for (std::size_t i = 0; i < envs_.size(); ++i) {
    if (mask == nullptr || mask[i]) {
      envs_[i]->reset(rngs_[i]);
      ended_[i] = 0;
    }
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

void EnvBatch::step(const double* actions, const BatchStep& out) {
  if (autoreset_ == Autoreset::SameStep && (out.finalObs == nullptr || out.finalMask == nullptr)) {
    throw std::logic_error("EnvBatch::step: same-step autoreset needs finalObs and finalMask");
  }
  const std::size_t components = space_.components;
  for (std::size_t i = 0; i < envs_.size(); ++i) checkAction(i, actions + i * components);
  for (std::size_t i = 0; i < envs_.size(); ++i) {
    double* row = out.obs + i * dim_;
    if (out.finalMask != nullptr) out.finalMask[i] = false;
    if (autoreset_ == Autoreset::NextStep && ended_[i]) {
      envs_[i]->reset(rngs_[i]);
      ended_[i] = 0;
      writeState(i, row);
      out.rewards[i] = 0.0;
      out.terminated[i] = false;
      out.truncated[i] = false;
      continue;
    }
    const double* action = actions + i * components;
    if (kind_ == ActionKind::Tetris) {
      legalTetrisAction(*envs_[i], action, action_.data());
      action = action_.data();
    }
    const env::StepResult result = envs_[i]->step(std::span<const double>(action, components));
    out.rewards[i] = result.reward;
    out.terminated[i] = result.terminated;
    out.truncated[i] = result.truncated;
    const bool ended = result.terminated || result.truncated;
    if (ended && autoreset_ == Autoreset::SameStep) {
      writeState(i, out.finalObs + i * dim_);
      out.finalMask[i] = true;
      envs_[i]->reset(rngs_[i]);
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
