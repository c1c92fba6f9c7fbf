// python: the instances of an EnvBatch that has a batched environment (env/batch.hpp): their
// states, step counts and results live in the batch's structure-of-arrays buffers, and one call of
// BatchEnvironment::step moves them all. Read and written here one instance (lane) at a time, in
// the row layout that EnvBatch and NumPy use.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

#include "gpfd/env/batch.hpp"
#include "gpfd/util/rng.hpp"

namespace gpfd::python {

class BatchLanes {
 public:
  // `n` lanes, each starting in `start` (the state of a freshly made scalar environment, as the
  // loop path's instances start) with a step count of 0.
  BatchLanes(std::unique_ptr<env::BatchEnvironment> batch, std::size_t n,
             std::span<const double> start);

  std::size_t size() const { return lanes_.buffers().lanes; }
  // Starts an episode in `lane` from `rng`, exactly as the scalar environment's reset.
  void reset(std::size_t lane, Rng& rng) { batch_->reset(rng, lanes_.buffers(), lane); }
  // Steps every lane; actions: size() rows of actionComponents() values, already checked.
  void step(const double* actions);
  // The lane's state variables as a row of stateDim() values.
  void readState(std::size_t lane, double* row) const;
  // Sets the lane's state variables (checked by the caller) and restarts its step count, as
  // Environment::setState does.
  void writeState(std::size_t lane, std::span<const double> row);
  // The steps of the lane's episode so far (what its time limit reads), and setting them (after
  // writeState, to restore a lane).
  std::int32_t elapsed(std::size_t lane) const { return lanes_.elapsed[lane]; }
  void setElapsed(std::size_t lane, std::int32_t steps) { lanes_.elapsed[lane] = steps; }

  // What the last step() gave the lane.
  env::StepResult result(std::size_t lane) const {
    return {lanes_.reward[lane], lanes_.terminated[lane] != 0, lanes_.truncated[lane] != 0};
  }

 private:
  std::unique_ptr<env::BatchEnvironment> batch_;
  std::size_t dim_, components_;
  // Rows of n rounded up to a group of four lanes (the tail is scratch for AVX2).
  env::BatchStorage lanes_;
};

}  // namespace gpfd::python
