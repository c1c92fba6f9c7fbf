// env: batched environments: many independent instances of one environment stepped in one call.
//
// Layout (structure of arrays): with `stride` >= the number of lanes, state variable i of lane l
// is state[i * stride + l] and action component c of lane l is action[c * stride + l]; so a NumPy
// array of shape (stateDim, stride), C order, is a state buffer as it is. Per lane: `elapsed`
// counts the steps of its episode (the time limit reads it), `reward`, `terminated` and
// `truncated` receive what Environment::step returns.
//
// Every lane gives, bit for bit, what the scalar environment's step() gives from the same state,
// step count and action: both run the same dynamics templates (cartpole_dynamics.hpp, ...), on
// eight lanes at a time with AVX-512 or four with AVX2 where the CPU has them (util/cpu.hpp), one
// lane at a time otherwise. tests/env/test_batch.cpp checks it on random states and actions, every
// way. An environment declares its batched form in its registry entry (EnvInfo::batch), so a
// plug-in's can have one; makeLaneByLaneBatch steps copies of any environment instead
// (tests/env/test_batch_forms.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::env {

struct BatchBuffers {
  std::size_t lanes = 0;               // Instances stepped: lanes [0, lanes).
  std::size_t stride = 0;              // Distance between rows of `state` and `action` (>= lanes).
  double* state = nullptr;             // In/out: stateDim() rows of `stride`.
  const double* action = nullptr;      // In: actionComponents() rows of `stride`.
  std::int32_t* elapsed = nullptr;     // In/out: steps of the episode so far; +1 per step.
  double* reward = nullptr;            // Out: `lanes` values.
  std::uint8_t* terminated = nullptr;  // Out: 1 for a terminal state of the task.
  std::uint8_t* truncated = nullptr;   // Out: 1 when the time limit is reached.
  // True: the lanes from `lanes` up to the next multiple of 4 (within `stride` and every per-lane
  // array) are scratch that the AVX2 path may overwrite with garbage, which spares it copying a
  // last partial group of lanes. False (default): nothing beyond `lanes` is touched.
  bool scratchTail = false;
};

// Owns the buffers of a batch: rows of `stride` for `lanes` lanes, zero-filled, and the
// BatchBuffers that point into them (its `lanes` and `scratchTail` may be changed between steps).
// Neither copied nor moved, so that the pointers stay valid.
class BatchStorage {
 public:
  BatchStorage(std::size_t lanes, std::size_t stride, std::size_t stateDim,
               std::size_t actionComponents);
  BatchStorage(const BatchStorage&) = delete;
  BatchStorage& operator=(const BatchStorage&) = delete;

  BatchBuffers& buffers() { return io_; }
  const BatchBuffers& buffers() const { return io_; }

  std::vector<double> state, action, reward;
  std::vector<std::int32_t> elapsed;
  std::vector<std::uint8_t> terminated, truncated;

 private:
  BatchBuffers io_;
};

// How lanes are computed: Auto takes the widest the CPU offers (util/cpu.hpp), Scalar one lane at
// a time (the fallback, and for tests); Avx2 (four lanes per instruction) and Avx512 (cart-pole and
// Acrobot eight lanes per instruction, the swimmer four) insist (std::invalid_argument where the
// CPU lacks them).
enum class BatchIsa { Auto, Avx512, Avx2, Scalar };

class BatchEnvironment {
 public:
  virtual ~BatchEnvironment() = default;

  // The scalar environment whose steps the lanes reproduce (its parameters, its reset).
  const Environment& scalar() const { return *scalar_; }
  std::size_t stateDim() const { return scalar_->stateDim(); }
  std::size_t actionComponents() const { return scalar_->actionSpace().components; }
  // The instruction set in use (resolved: Avx512, Avx2 or Scalar). usesAvx2(): AVX2 at least, so
  // that lane kernels of util/lanes.hpp marked GPFD_AVX2_KERNEL may run.
  BatchIsa isa() const { return isa_; }
  bool usesAvx2() const { return isa_ != BatchIsa::Scalar; }

  // Starts an episode in lane `lane`: its state is drawn from `rng` exactly as scalar().reset
  // draws it, and elapsed[lane] = 0.
  virtual void reset(Rng& rng, const BatchBuffers& io, std::size_t lane);
  // Starts an episode in every lane l < rngs.size() (<= io.stride) as reset(rngs[l], io, l) does,
  // in lane order; whatever episodes the lanes held before are dropped. The lockstep player
  // starts each call's episodes through it, so that a form whose lanes reset together (a Python
  // vector environment: one reset call for all) may. The default calls reset() lane by lane.
  virtual void resetAll(std::span<Rng> rngs, const BatchBuffers& io);
  // One step of every lane. Throws InputError (naming the lane) for a discrete action that is not
  // one of the choices, before any lane moves; continuous actions are clipped, NaN taken as 0.
  virtual void step(const BatchBuffers& io) const = 0;
  // The episode of lane `from` moves to lane `to` (the caller has moved its rows of the buffers);
  // the episode that lane `to` held is dropped. Nothing to do for a form whose lanes live wholly
  // in the buffers (the default).
  virtual void moveLane(std::size_t /*from*/, std::size_t /*to*/) {}

 protected:
  // `isa` must be resolved (Avx512, Avx2 or Scalar).
  BatchEnvironment(std::unique_ptr<Environment> scalar, BatchIsa isa)
      : scalar_(std::move(scalar)), isa_(isa) {}

 private:
  std::unique_ptr<Environment> scalar_;
  BatchIsa isa_;
};

// The batched form of `env` (a copy of its parameters) that its registry entry declares
// (EnvInfo::batch, looked up by env.name()), or nullptr when it has none: cart-pole and Acrobot
// always, the swimmer when it steps with its fixed-size kernel (at most 8 segments, reference
// solver off); a plug-in's environment where it declares one. Tetris has none (its learner
// evaluates afterstates in bulk instead).
std::unique_ptr<BatchEnvironment> makeBatchEnvironment(const Environment& env,
                                                       BatchIsa isa = BatchIsa::Auto);
// Whether makeBatchEnvironment(env) gives a batched form; cheap (nothing is made).
bool hasBatchEnvironment(const Environment& env);
// The same by registry name and parameters (Python's vector environment); InputError when the
// environment has no batched form.
std::unique_ptr<BatchEnvironment> makeBatchEnvironment(const std::string& name,
                                                       const Params& params,
                                                       BatchIsa isa = BatchIsa::Auto);

// Any environment as a batch, lane by lane: lane l steps its own fresh copy of `env`
// (Environment::freshCopy) through step(), one lane after another; nullptr when `env` cannot be
// copied (a twin of a Gymnasium task: its makeLanes, the same contract). Each lane's copy keeps its
// state: the `state` rows are written (after reset and step) but not read, so lanes move only
// through moveLane. A discrete action that is not one of the choices throws InputError before any
// lane moves for a one-component action; otherwise the copy's step() throws, the lanes before it
// having moved. `isa` tells the caller's lane kernels what they may use (usesAvx2); the copies step
// one at a time whatever it is.
std::unique_ptr<BatchEnvironment> makeLaneByLaneBatch(const Environment& env,
                                                      BatchIsa isa = BatchIsa::Auto);

}  // namespace gpfd::env
