#include "batch_lanes.hpp"

#include <utility>

namespace gpfd::python {

BatchLanes::BatchLanes(std::unique_ptr<env::BatchEnvironment> batch, std::size_t n,
                       std::span<const double> start)
    : batch_(std::move(batch)),
      dim_(batch_->stateDim()),
      components_(batch_->actionComponents()),
      lanes_(n, (n + 3) / 4 * 4, dim_, components_) {
  lanes_.buffers().scratchTail = true;  // The lanes up to the stride are scratch.
  for (std::size_t l = 0; l < n; ++l) writeState(l, start);
}

void BatchLanes::step(const double* actions) {
  const std::size_t stride = lanes_.buffers().stride;
  for (std::size_t l = 0; l < size(); ++l) {
    for (std::size_t c = 0; c < components_; ++c) {
      lanes_.action[c * stride + l] = actions[l * components_ + c];
    }
  }
  batch_->step(lanes_.buffers());
}

void BatchLanes::readState(std::size_t lane, double* row) const {
  const std::size_t stride = lanes_.buffers().stride;
  for (std::size_t i = 0; i < dim_; ++i) row[i] = lanes_.state[i * stride + lane];
}

void BatchLanes::writeState(std::size_t lane, std::span<const double> row) {
  const std::size_t stride = lanes_.buffers().stride;
  for (std::size_t i = 0; i < dim_; ++i) lanes_.state[i * stride + lane] = row[i];
  lanes_.elapsed[lane] = 0;
}

}  // namespace gpfd::python
