// env: the batched forms of the built-in environments (env/batch.hpp), one maker per environment.
#pragma once

#include <memory>

#include "gpfd/env/acrobot.hpp"
#include "gpfd/env/batch.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/swimmer.hpp"

namespace gpfd::env::batch {

// `isa` is resolved (Avx2 or Scalar).
std::unique_ptr<BatchEnvironment> makeCartPole(const CartPole& env, BatchIsa isa);
std::unique_ptr<BatchEnvironment> makeAcrobot(const Acrobot& env, BatchIsa isa);
// nullptr unless the swimmer steps with its fixed-size kernel.
std::unique_ptr<BatchEnvironment> makeSwimmer(const Swimmer& env, BatchIsa isa);

}  // namespace gpfd::env::batch
