// python: N instances of one gpfd environment stepped together, each with its own random stream:
// the engine of gpfd's Gymnasium environments (N = 1) and of their vector environment. Plain C++
// without Python, so that batched kernels can replace the loop over scalar environments here
// without touching the bindings.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::python {

// What happens to an instance whose episode ended (Gymnasium's autoreset modes).
enum class Autoreset {
  NextStep,  // The next step() resets it and ignores its action (reward 0, not done).
  SameStep,  // step() resets it at once and reports the last observation in finalObs.
  Disabled,  // Nothing: the caller resets it.
};
Autoreset parseAutoreset(const std::string& name);  // next_step | same_step | disabled.

// How an action given as numbers reaches the environment.
enum class ActionKind {
  Continuous,  // components values, clipped by the environment.
  Discrete,    // One integer in [0, choices).
  Tetris,      // (orientation, column), mapped to the nearest legal placement (legalTetrisAction).
};

// Caller-owned output of one step of the batch.
struct BatchStep {
  double* obs = nullptr;       // n x stateDim
  double* rewards = nullptr;   // n
  bool* terminated = nullptr;  // n
  bool* truncated = nullptr;   // n
  double* finalObs = nullptr;  // SameStep: n x stateDim, the last observation of ended episodes
  bool* finalMask = nullptr;   // SameStep: n, the rows of finalObs that are set
};

class EnvBatch {
 public:
  // InputError for an unknown environment or parameter, or an action space that cannot be driven
  // by numbers (a discrete space of several components other than Tetris).
  EnvBatch(const std::string& name, const Params& params, std::size_t n, Autoreset autoreset);
  EnvBatch(const EnvBatch&) = delete;
  EnvBatch& operator=(const EnvBatch&) = delete;

  std::size_t size() const { return envs_.size(); }
  std::size_t stateDim() const { return dim_; }
  std::size_t actionComponents() const { return space_.components; }
  ActionKind actionKind() const { return kind_; }
  Autoreset autoreset() const { return autoreset_; }
  const env::ActionSpace& actionSpace() const { return space_; }
  env::Environment& env(std::size_t i) { return *envs_.at(i); }
  const env::Environment& env(std::size_t i) const { return *envs_.at(i); }

  // Reseeds instance i's stream; its next reset starts from Rng(seed), like
  // `gpfd simulate --seed seed`.
  void seed(std::size_t i, std::uint64_t seed) { rngs_.at(i).reseed(seed); }
  // Resets the instances with mask[i] (all when mask is null); writes every instance's
  // observation to obs (n x stateDim).
  void reset(const bool* mask, double* obs);
  // Applies actions (n x actionComponents) to every instance. Checks every action before it
  // steps any instance (InputError naming the instance and the value).
  void step(const double* actions, const BatchStep& out);

 private:
  void checkAction(std::size_t i, const double* action) const;
  void writeState(std::size_t i, double* row) const;

  std::vector<std::unique_ptr<env::Environment>> envs_;
  std::vector<Rng> rngs_;
  std::vector<char> ended_;  // NextStep: the episode ended at the previous step.
  env::ActionSpace space_;
  ActionKind kind_ = ActionKind::Continuous;
  Autoreset autoreset_;
  std::size_t dim_ = 0;
  std::vector<double> action_;  // One instance's action, after mapping.
};

// The legal placement nearest to (orientation, column) for Tetris' current piece: the orientation
// taken modulo the piece's orientation count, the column clipped to where that orientation fits.
// InputError for a negative or fractional component.
void legalTetrisAction(const env::Environment& tetris, const double* action, double* legal);

// Tetris' legal placements as a mask of orientations (4) x columns, row-major.
std::vector<char> tetrisActionMask(const env::Environment& tetris);

}  // namespace gpfd::python
