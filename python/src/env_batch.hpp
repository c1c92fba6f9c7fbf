// python: N instances of one gpfd environment stepped together, each with its own random stream:
// the engine of gpfd's Gymnasium environments (N = 1) and of their vector environment. Plain C++
// without Python. Where the environment has a batched form (env/batch.hpp: cart-pole, Acrobot, the
// swimmer on its fixed-size kernel) the instances are lanes of it, all stepped by one call;
// otherwise (Tetris, plug-ins, Python environments) a loop steps one scalar environment per
// instance. Both give the same observations, rewards and flags, bit for bit.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "batch_lanes.hpp"
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

// How the instances are stepped.
enum class Engine {
  Auto,     // Batched where the environment has a batched form, else Loop.
  Loop,     // One scalar environment per instance, stepped one after another (the reference).
  Batched,  // Lanes of the batched environment; InputError where the environment has none.
};
Engine parseEngine(const std::string& name);  // auto | loop | batched.

// Caller-owned output of one step of the batch.
struct BatchStep {
  double* obs = nullptr;       // n x stateDim
  double* rewards = nullptr;   // n
  bool* terminated = nullptr;  // n
  bool* truncated = nullptr;   // n
  double* finalObs = nullptr;  // SameStep: n x stateDim, the last observation of ended episodes
  bool* finalMask = nullptr;   // SameStep: n, the rows of finalObs that are set
  // SameStep, optional: n x actionMaskSize(), the legal actions at finalObs' rows (those set).
  bool* finalLegal = nullptr;
};

class EnvBatch {
 public:
  // InputError for an unknown environment or parameter, or engine Batched for an environment
  // without a batched form or whose legal actions depend on the state (they are asked of each
  // instance, which only the loop path has).
  EnvBatch(const std::string& name, const Params& params, std::size_t n, Autoreset autoreset,
           Engine engine = Engine::Auto);
  EnvBatch(const EnvBatch&) = delete;
  EnvBatch& operator=(const EnvBatch&) = delete;

  std::size_t size() const { return rngs_.size(); }
  bool batched() const { return lanes_ != nullptr; }
  std::size_t stateDim() const { return dim_; }
  std::size_t actionComponents() const { return space_.components; }
  // Whether the legal discrete actions depend on the state (Environment::
  // hasStateDependentActions): then an action is mapped to the nearest legal one before it steps.
  bool stateDependentActions() const { return stateDependent_; }
  // Discrete spaces: the number of discrete actions (the product of the choices); 0 otherwise.
  std::size_t actionMaskSize() const { return maskSize_; }
  // Instance i's legal actions now (actionMaskSize() flags, row-major over the components); all
  // legal where they do not depend on the state. InputError for continuous actions.
  void legalActions(std::size_t i, bool* out) const;
  Autoreset autoreset() const { return autoreset_; }
  const env::ActionSpace& actionSpace() const { return space_; }
  // The environment's name, parameters, state names and spaces (instances' states: state()).
  const env::Environment& prototype() const { return *envs_.front(); }
  // Instance i's scalar environment on the loop path; nullptr on the batched path, whose
  // instances live in the batch's buffers. std::out_of_range for i >= size().
  const env::Environment* scalarInstance(std::size_t i) const;

  // Instance i's state variables (stateDim() values). std::out_of_range for i >= size().
  void state(std::size_t i, double* out) const;
  // Sets instance i's state variables exactly, with the environment's own checks (InputError),
  // and restarts its episode's step count (the time limit), as Environment::setState does.
  void setState(std::size_t i, std::span<const double> values);

  // Reseeds instance i's stream; its next reset starts from Rng(seed), like
  // `gpfd simulate --seed seed`.
  void seed(std::size_t i, std::uint64_t seed) { rngs_.at(i).reseed(seed); }
  // Resets the instances with mask[i] (all when mask is null); writes every instance's
  // observation to obs (n x stateDim).
  void reset(const bool* mask, double* obs);
  // Applies actions (n x actionComponents) to every instance. Checks every action before it
  // steps any instance (InputError naming the instance and the value): a discrete component is a
  // whole number in [0, choices) (any whole number >= 0 where the legal actions depend on the
  // state: the environment maps it to the nearest legal action); a continuous one is a number,
  // not NaN (Gymnasium's environments refuse invalid actions; the environment itself would take
  // NaN as 0), clipped by the environment.
  void step(const double* actions, const BatchStep& out);

  // Pickling (env_batch_state.cpp): every instance's whole dynamic state as words
  // (env/snapshot.hpp): its random stream, whether its episode ended (next-step autoreset), and
  // its environment's snapshot (loop) or its lane's state variables and step count (batched,
  // which by BatchEnvironment's contract determine the lane's next steps). InputError when the
  // environment has no snapshots (Environment::snapshot).
  std::vector<std::uint64_t> snapshot() const;
  // Takes back a snapshot of a batch of the same environment, parameters, size and engine;
  // InputError, nothing changed, for one that is not.
  void restore(std::span<const std::uint64_t> words);

 private:
  void checkAction(std::size_t i, const double* action) const;
  void resetInstance(std::size_t i);
  env::StepResult stepInstance(std::size_t i, const double* action);
  void writeState(std::size_t i, double* row) const;

  // The loop path: one environment per instance. The batched path: the prototype alone.
  std::vector<std::unique_ptr<env::Environment>> envs_;
  std::unique_ptr<BatchLanes> lanes_;  // The batched path's instances, or null.
  std::vector<Rng> rngs_;
  std::vector<char> ended_;  // NextStep: the episode ended at the previous step.
  env::ActionSpace space_;
  bool stateDependent_ = false;
  std::size_t maskSize_ = 0;
  Autoreset autoreset_;
  std::size_t dim_ = 0;
  std::vector<double> action_;  // One instance's action, after mapping.
};

}  // namespace gpfd::python
