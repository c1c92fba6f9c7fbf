#include "gpfd/env/batch.hpp"

#include <algorithm>
#include <stdexcept>

#include "batch_factories.hpp"
#include "gpfd/util/cpu.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {

namespace batch {

BatchIsa resolveIsa(BatchIsa isa) {
  if (isa == BatchIsa::Avx512 && !cpuHasAvx512()) {
    throw std::invalid_argument("batched environment: AVX-512 asked for but not available");
  }
  if (isa == BatchIsa::Avx2 && !cpuHasAvx2()) {
    throw std::invalid_argument("batched environment: AVX2 asked for but not available");
  }
  if (isa != BatchIsa::Auto) return isa;
  return cpuHasAvx512() ? BatchIsa::Avx512 : cpuHasAvx2() ? BatchIsa::Avx2 : BatchIsa::Scalar;
}

}  // namespace batch

namespace {

// The batched form that env's registry entry declares, if env has it; else nullptr.
const BatchForm* formOf(const Environment& env) {
  const EnvInfo* entry = Registry::global().find(env.name());
  if (entry == nullptr || !entry->batch.make) return nullptr;
  if (entry->batch.available && !entry->batch.available(env)) return nullptr;
  return &entry->batch;
}

}  // namespace

BatchStorage::BatchStorage(std::size_t lanes, std::size_t stride, std::size_t stateDim,
                           std::size_t actionComponents)
    : state(stateDim * stride, 0.0),
      action(actionComponents * stride, 0.0),
      reward(stride, 0.0),
      elapsed(stride, 0),
      terminated(stride, 0),
      truncated(stride, 0),
      io_{.lanes = lanes,
          .stride = stride,
          .state = state.data(),
          .action = action.data(),
          .elapsed = elapsed.data(),
          .reward = reward.data(),
          .terminated = terminated.data(),
          .truncated = truncated.data()} {}

void BatchEnvironment::reset(Rng& rng, const BatchBuffers& io, std::size_t lane) {
  scalar_->reset(rng);
  const auto state = scalar_->state();
  for (std::size_t i = 0; i < state.size(); ++i) io.state[i * io.stride + lane] = state[i];
  io.elapsed[lane] = 0;
}

void BatchEnvironment::resetAll(std::span<Rng> rngs, const BatchBuffers& io) {
  for (std::size_t lane = 0; lane < rngs.size(); ++lane) reset(rngs[lane], io, lane);
}

bool hasBatchEnvironment(const Environment& env) { return formOf(env) != nullptr; }

std::unique_ptr<BatchEnvironment> makeBatchEnvironment(const Environment& env, BatchIsa isa) {
  const BatchForm* form = formOf(env);
  return form != nullptr ? form->make(env, batch::resolveIsa(isa)) : nullptr;
}

std::unique_ptr<BatchEnvironment> makeBatchEnvironment(const std::string& name,
                                                       const Params& params, BatchIsa isa) {
  auto batch = makeBatchEnvironment(*Registry::global().make(name, params), isa);
  if (!batch) throw InputError(name + " has no batched form", "batched environment");
  return batch;
}

}  // namespace gpfd::env
