// env: the batched forms of the built-in environments (env/batch.hpp), one maker per environment.
#pragma once

#include <memory>
#include <type_traits>

#include "gpfd/env/acrobot.hpp"
#include "gpfd/env/batch.hpp"
#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/swimmer.hpp"

namespace gpfd::env::batch {

// Avx512 or Avx2 when the CPU has them (std::invalid_argument otherwise), the widest the CPU
// offers for Auto, Scalar as it is.
BatchIsa resolveIsa(BatchIsa isa);

// `isa` is resolved (Avx512, Avx2 or Scalar). Each maker is its environment's BatchForm::make
// (registered where its EnvInfo is built).
std::unique_ptr<BatchEnvironment> makeCartPole(const CartPole& env, BatchIsa isa);
std::unique_ptr<BatchEnvironment> makeAcrobot(const Acrobot& env, BatchIsa isa);
// nullptr unless the swimmer steps with its fixed-size kernel.
std::unique_ptr<BatchEnvironment> makeSwimmer(const Swimmer& env, BatchIsa isa);

// The BatchForm (EnvInfo::batch) of environment type Env whose batched form `make` builds: every
// Env has it, or those for which `has` says so.
template <class Env>
BatchForm formOf(std::unique_ptr<BatchEnvironment> (*make)(const Env&, BatchIsa),
                 std::type_identity_t<bool (*)(const Env&)> has = nullptr) {
  return {[has](const Environment& env) {
            const auto* typed = dynamic_cast<const Env*>(&env);
            return typed != nullptr && (has == nullptr || has(*typed));
          },
          [make](const Environment& env, BatchIsa isa) {
            return make(dynamic_cast<const Env&>(env), isa);
          }};
}

}  // namespace gpfd::env::batch
