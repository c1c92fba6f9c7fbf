// env: the environment interface every benchmark implements, and the registry that makes
// environments by name. No GP in this module.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpfd/util/named_registry.hpp"
#include "gpfd/util/params.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::env {

// Parameter values by name, as given in a config or on the command line (`k=v`), and the
// declaration of one parameter (util/params.hpp).
using gpfd::Params;
using gpfd::ParamSpec;

// The typical range of one state variable: exact where the dynamics bound it, otherwise the
// values seen in episodes. The Fourier basis scales states to [0, 1] with it.
struct StateRange {
  double low = 0.0;
  double high = 1.0;
};

class AfterstateGame;
class BatchEnvironment;  // env/batch.hpp
enum class BatchIsa;     // env/batch.hpp

// A continuous box (one [low, high] per dimension) or a set of discrete choices. A discrete
// action is passed to step() as its components, each a whole number in [0, choices[c]) (one
// component, the choice index, for a plain discrete space; Tetris uses two: orientation and
// column). Which of them are legal may depend on the state (Environment::
// hasStateDependentActions). This is all a front needs to drive an environment (Gymnasium: a Box,
// Discrete(choices[0]) or MultiDiscrete(choices), with a mask of the legal actions).
struct ActionSpace {
  enum class Kind { Continuous, Discrete };
  Kind kind = Kind::Continuous;
  std::vector<double> low;         // Continuous: lower bound per dimension.
  std::vector<double> high;        // Continuous: upper bound per dimension.
  std::vector<int> choices;        // Discrete: the number of choices of each component.
  std::size_t components = 1;      // Number of components in an action passed to step().
  std::vector<std::string> names;  // One name per component (CSV headers, listings).

  bool continuous() const { return kind == Kind::Continuous; }
  // Discrete: the number of discrete actions, the product of the choices (the size of a mask of
  // legal actions, row-major over the components); 0 for a continuous space.
  std::size_t discreteActions() const;
};

struct StepResult {
  double reward = 0.0;
  bool terminated = false;  // A terminal state of the task (failure, goal, game over).
  bool truncated = false;   // The time limit was reached; the state is not terminal.
};

// Contract: an Environment owns no global state, logs nothing in step(), and is used by one
// thread at a time; make one instance per trial (see Registry::make). An episode depends only on
// the parameters, the draws reset() makes from its Rng and the actions, not on earlier episodes
// nor on which instance plays it (the lockstep player relies on it).
class Environment {
 public:
  virtual ~Environment() = default;

  virtual std::string name() const = 0;
  // Every parameter of this instance with its resolved value (defaults filled in), as text that
  // Registry::make accepts back.
  virtual Params params() const = 0;
  // Names of the state variables, in the order of state().
  virtual const std::vector<std::string>& stateNames() const = 0;
  std::size_t stateDim() const { return stateNames().size(); }
  virtual ActionSpace actionSpace() const = 0;

  // Starts an episode from the environment's start distribution.
  virtual void reset(Rng& rng) = 0;
  // The current state variables, stateDim() values, valid until the next call of a non-const
  // member.
  virtual std::span<const double> state() const = 0;
  // Sets the state variables exactly (tests, replays); throws InputError on a wrong size or a
  // state the environment cannot take.
  virtual void setState(std::span<const double> state) = 0;
  // Applies one action (continuous components are clipped to the bounds).
  // A NaN component is taken as 0. A discrete component that is not one of the choices throws
  // InputError. Stepping on after a terminal state is allowed (the dynamics simply continue) except
  // where an environment documents otherwise.
  virtual StepResult step(std::span<const double> action) = 0;

  // Writes a uniformly random legal action (actionSpace().components values) into `action`: uniform
  // in the box for continuous spaces, a uniform choice for discrete ones. Environments whose legal
  // actions depend on the state (Tetris) override it.
  virtual void sampleAction(Rng& rng, std::span<double> action) const;

  // Discrete spaces, for fronts that drive the environment with actions from outside (Python):
  // Whether which actions are legal depends on the state (Tetris: the current piece's
  // placements). False (the default): every action of the space is legal in every state.
  virtual bool hasStateDependentActions() const { return false; }
  // Writes 1 for each legal action now and 0 for the others (actionSpace().discreteActions()
  // flags, row-major over the components; Tetris: orientation x column). The default marks all
  // legal. InputError when `mask` has another size.
  virtual void legalActionMask(std::span<std::uint8_t> mask) const;
  // The legal action nearest to `action` (components that are whole numbers >= 0, possibly beyond
  // the choices), written into `legal` (components values). The default copies `action`; Tetris
  // takes the orientation modulo the piece's orientation count and clips the column to where that
  // orientation fits.
  virtual void nearestLegalAction(std::span<const double> action, std::span<double> legal) const;

  // What an environment knows about itself, for the learners and feature sets that ask:
  // One typical range per state variable (empty: none known, so no Fourier basis).
  virtual std::vector<StateRange> typicalStateRanges() const { return {}; }
  // The afterstate view of a game whose moves are chosen by looking one move ahead (Tetris), for
  // learners that need it (afterstate_game.hpp); nullptr for the others. Valid while this lives.
  virtual AfterstateGame* afterstateGame() { return nullptr; }

  // A new instance with this one's parameters and settings but not its state (reset() starts it),
  // or nullptr where none can be made. The lockstep player steps such copies lane by lane when
  // the environment has no batched form (env/batch.hpp). The default makes one with
  // Registry::global() from name() and params(): nullptr when the name is not registered, the
  // entry refuses those parameters or makes another type. An environment with settings beyond
  // params() overrides it.
  virtual std::unique_ptr<Environment> freshCopy() const;

  // The whole dynamic state as words (env/snapshot.hpp): the state variables and whatever else
  // the next steps depend on (the episode's step count; Tetris' board, piece, piece generator and
  // game-over flag), so that restore() on an instance with the same parameters continues exactly
  // as this one, bit for bit (Python pickles environments with it). Empty where the environment
  // has none: the default, which an environment overrides together with restore().
  virtual std::vector<std::uint64_t> snapshot() const { return {}; }
  // Takes back a snapshot of an instance with the same parameters; InputError, nothing changed,
  // for words that are not one. The default refuses every snapshot.
  virtual void restore(std::span<const std::uint64_t> words);
};

using Factory = std::function<std::unique_ptr<Environment>(const Params&)>;

// An environment's batched form (env/batch.hpp): many instances stepped in one call, every lane
// bit for bit what the scalar step() gives. `make` empty: none.
struct BatchForm {
  // Whether `env` (an instance of this entry) has the batched form; cheap, nothing made. Empty:
  // every instance has it.
  std::function<bool(const Environment& env)> available;
  // The batched form of `prototype` (a copy of its parameters); called only where available.
  // `isa` is resolved (Avx512, Avx2 or Scalar): the form hands it to BatchEnvironment's
  // constructor and may use it or step one lane at a time whatever it is.
  std::function<std::unique_ptr<BatchEnvironment>(const Environment& prototype, BatchIsa isa)> make;
};

// What the registry knows about one environment.
struct EnvInfo {
  std::string name;
  std::string description;
  std::vector<ParamSpec> params;
  Factory make;
  std::string defaultLearner = "pg";  // The learner that commands use unless told otherwise.
  BatchForm batch = {};               // Its batched form, if it has one.
};

// Maps names to factories. The built-in environments are registered on first use (one line each
// in src/env/registry.cpp); plug-ins and programs add their own with add() (docs/environments.md).
// info(name), find(name) and names() come from NamedRegistry.
class Registry : public NamedRegistry<EnvInfo> {
 public:
  Registry() : NamedRegistry("environment") {}
  static Registry& global();

  // Throws InputError when the name is taken, the factory missing, or a batched form has
  // `available` without `make`.
  void add(EnvInfo info);
  // Validates the parameter names against info(name).params (InputError on an unknown one) and
  // makes a fresh instance.
  std::unique_ptr<Environment> make(const std::string& name, const Params& params = {}) const;
};

}  // namespace gpfd::env
