#include "gpfd/env/batch.hpp"

#include <algorithm>
#include <stdexcept>

#include "batch_factories.hpp"
#include "gpfd/util/cpu.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

BatchIsa resolve(BatchIsa isa) {
  if (isa == BatchIsa::Avx2 && !cpuHasAvx2()) {
    throw std::invalid_argument("batched environment: AVX2 asked for but not available");
  }
  if (isa == BatchIsa::Auto) return cpuHasAvx2() ? BatchIsa::Avx2 : BatchIsa::Scalar;
  return isa;
}

}  // namespace

void BatchEnvironment::reset(Rng& rng, const BatchBuffers& io, std::size_t lane) {
  scalar_->reset(rng);
  const auto state = scalar_->state();
  for (std::size_t i = 0; i < state.size(); ++i) io.state[i * io.stride + lane] = state[i];
  io.elapsed[lane] = 0;
}

std::unique_ptr<BatchEnvironment> makeBatchEnvironment(const Environment& env, BatchIsa isa) {
  if (const auto* cartPole = dynamic_cast<const CartPole*>(&env)) {
    return batch::makeCartPole(*cartPole, resolve(isa));
  }
  if (const auto* acrobot = dynamic_cast<const Acrobot*>(&env)) {
    return batch::makeAcrobot(*acrobot, resolve(isa));
  }
  if (const auto* swimmer = dynamic_cast<const Swimmer*>(&env)) {
    return batch::makeSwimmer(*swimmer, resolve(isa));
  }
  return nullptr;
}

std::unique_ptr<BatchEnvironment> makeBatchEnvironment(const std::string& name,
                                                       const Params& params, BatchIsa isa) {
  auto batch = makeBatchEnvironment(*Registry::global().make(name, params), isa);
  if (!batch) throw InputError(name + " has no batched form", "batched environment");
  return batch;
}

}  // namespace gpfd::env
