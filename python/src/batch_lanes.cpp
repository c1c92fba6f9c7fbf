#include "batch_lanes.hpp"

#include <utility>

namespace gpfd::python {

BatchLanes::BatchLanes(std::unique_ptr<env::BatchEnvironment> batch, std::size_t n,
                       std::span<const double> start)
    : batch_(std::move(batch)), dim_(batch_->stateDim()), components_(batch_->actionComponents()) {
  const std::size_t stride = (n + 3) / 4 * 4;
  state_.assign(dim_ * stride, 0.0);
  action_.assign(components_ * stride, 0.0);
  reward_.assign(stride, 0.0);
  elapsed_.assign(stride, 0);
  terminated_.assign(stride, 0);
  truncated_.assign(stride, 0);
  io_ = {.lanes = n,
         .stride = stride,
         .state = state_.data(),
         .action = action_.data(),
         .elapsed = elapsed_.data(),
         .reward = reward_.data(),
         .terminated = terminated_.data(),
         .truncated = truncated_.data(),
         .scratchTail = true};  // The lanes up to `stride` are scratch.
  for (std::size_t l = 0; l < n; ++l) writeState(l, start);
}

void BatchLanes::step(const double* actions) {
  const std::size_t stride = io_.stride;
  for (std::size_t l = 0; l < io_.lanes; ++l) {
    for (std::size_t c = 0; c < components_; ++c) {
      action_[c * stride + l] = actions[l * components_ + c];
    }
  }
  batch_->step(io_);
}

void BatchLanes::readState(std::size_t lane, double* row) const {
  for (std::size_t i = 0; i < dim_; ++i) row[i] = state_[i * io_.stride + lane];
}

void BatchLanes::writeState(std::size_t lane, std::span<const double> row) {
  for (std::size_t i = 0; i < dim_; ++i) state_[i * io_.stride + lane] = row[i];
  elapsed_[lane] = 0;
}

}  // namespace gpfd::python
