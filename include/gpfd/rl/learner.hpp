// rl: the learner registry. Every learner is reached by name through it (`gpfd train`, `assess`,
// `evolve`, `reproduce`, configs): it declares its parameters once (parsing, printing, checking,
// --help), what it needs from an environment, the parameter that sets its budget, and how it
// trains. The built-in learners are registered on first use, one line each in
// src/rl/learner_registry.cpp; plug-ins and programs add their own with add() (docs/learners.md).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/learning_curve.hpp"
#include "gpfd/util/params.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::rl {

// Called with each row of a learning curve as soon as it is complete (progress output).
using PointCallback = std::function<void(const CurvePoint&)>;
// The same for several runs: the index of the run and the row.
using RunPointCallback = std::function<void(std::size_t run, const CurvePoint&)>;
// Makes a fresh instance of the environment a run learns on.
using EnvironmentMaker = std::function<std::unique_ptr<env::Environment>()>;

// Greedy play with trained weights.
struct Evaluation {
  int episodes = 0;
  double meanReturn = 0.0;
  std::int64_t steps = 0;
  bool diverged = false;
};

// A learner with its settings applied. Its members are const and keep no state between calls,
// so one instance serves many runs on many threads.
class Learner {
 public:
  virtual ~Learner() = default;
  // One learning run from scratch on `env` (a fresh instance the learner can learn on), seeing
  // states through `map` (map.inputDim() == env.stateDim()). Numerical trouble marks the curve
  // diverged and never throws; bad settings throw InputError.
  virtual LearningCurve train(env::Environment& env, const features::FeatureMap& map, Rng& rng,
                              const PointCallback& onPoint = {}) const = 0;
  // Several independent runs from scratch, run k drawing from rngs[k] (the trials of a fitness
  // evaluation): curve k is exactly what train(*makeEnv(), map, rngs[k]) gives, bit for bit
  // (wallSeconds aside), and rngs[k] is left as that call leaves it. The default trains them one
  // after another, each on its own environment; a learner may override it to play them together
  // (pg with lockstep). onPoint sees each run's rows in order, those of different runs possibly
  // interleaved.
  virtual std::vector<LearningCurve> trainRuns(const EnvironmentMaker& makeEnv,
                                               const features::FeatureMap& map, std::span<Rng> rngs,
                                               const RunPointCallback& onPoint = {}) const;
  // Plays `episodes` episodes greedily with `weights` as train() returned them.
  virtual Evaluation evaluate(env::Environment& env, const features::FeatureMap& map,
                              const LinearWeights& weights, int episodes, Rng& rng) const = 0;
};

// What the registry knows about one learner.
struct LearnerInfo {
  std::string name;
  std::string description;
  std::vector<ParamSpec> params;
  // Makes the learner from its parameters (names already checked against `params`); InputError
  // for a value it cannot take.
  std::function<std::unique_ptr<Learner>(const Params&)> make;
  // What it needs from an environment, in words, and why it cannot learn on a given one (empty
  // when it can).
  std::string needs;
  std::function<std::string(env::Environment&)> unsuitable;
  // The parameter that sets the length of a run (`gpfd assess --budget`), and what one row of its
  // learning curve after the first stands for (plots).
  std::string budgetParam;
  std::string rowName;
  // The episodes one row of its learning curve plays, from its parameters (pg's episodes, ars's
  // 2 n_delta, lpi's games), so that a training of B (budgetParam) plays (B + 1) times as many:
  // learner.choose compares another learner at the same episodes (run/learner_choice.hpp). Empty
  // where the count is not fixed; such a learner is no other learner's candidate.
  std::function<std::int64_t(const Params&)> rowEpisodes;
};

// info(name) and names() come from NamedRegistry.
class LearnerRegistry : public NamedRegistry<LearnerInfo> {
 public:
  LearnerRegistry() : NamedRegistry("learner") {}
  static LearnerRegistry& global();

  // Throws InputError when the name is taken or the entry is incomplete.
  void add(LearnerInfo info);
  // Checks the parameter names against info(name).params (InputError "<name>.<key>" on an unknown
  // one) and makes the learner.
  std::unique_ptr<Learner> make(const std::string& name, const Params& params) const;
  // InputError when learner `name` cannot learn on `env`.
  void checkSuitable(const std::string& name, env::Environment& env) const;
};

}  // namespace gpfd::rl
