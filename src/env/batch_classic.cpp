// env: batched cart-pole and Acrobot.
#include "acrobot_dynamics.hpp"
#include "batch_driver.hpp"
#include "batch_factories.hpp"
#include "cartpole_dynamics.hpp"

namespace gpfd::env::batch {
namespace {

struct CartPoleKernel {
  CartPoleConfig config;

  template <class T>
  lanes::MaskOf<T> operator()(std::array<T, 4>& s, const std::array<T, 1>& a, T& reward) const {
    cartpole::advance(config, s, cartpole::force(config, a[0]));
    reward = 1.0;
    return cartpole::terminal(s);
  }
};

struct AcrobotKernel {
  AcrobotConfig config;

  template <class T>
  lanes::MaskOf<T> operator()(std::array<T, 4>& s, const std::array<T, 1>& a, T& reward) const {
    acrobot::advance(config, s, acrobot::torque(config, a[0]));
    const auto done = acrobot::terminal(s);
    reward = lanes::select(done, T(0.0), T(-1.0));
    return done;
  }
};

// Cart-pole or Acrobot: four state variables, one action component, `choices` discrete actions.
template <class Env, class Kernel, int choices>
class ClassicBatch final : public BatchEnvironment {
 public:
  ClassicBatch(const Env& env, BatchIsa isa)
      : BatchEnvironment(std::make_unique<Env>(env.config()), isa), kernel_{env.config()} {}

  void step(const BatchBuffers& io) const override {
    if (kernel_.config.discrete) checkChoices(io, choices, scalar().name());
    stepAll<4, 1, true>(kernel_, io, isa(), kernel_.config.maxSteps);
  }

 private:
  Kernel kernel_;
};

}  // namespace

std::unique_ptr<BatchEnvironment> makeCartPole(const CartPole& env, BatchIsa isa) {
  return std::make_unique<ClassicBatch<CartPole, CartPoleKernel, 2>>(env, isa);
}

std::unique_ptr<BatchEnvironment> makeAcrobot(const Acrobot& env, BatchIsa isa) {
  return std::make_unique<ClassicBatch<Acrobot, AcrobotKernel, 3>>(env, isa);
}

}  // namespace gpfd::env::batch
