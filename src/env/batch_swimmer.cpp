// env: the batched swimmer, on the fixed-size kernel (swimmer_kernel.hpp) with its segment count
// as a template argument.
#include <utility>

#include "batch_driver.hpp"
#include "batch_factories.hpp"
#include "swimmer_kernel.hpp"

namespace gpfd::env::batch {
namespace {

template <int N>
struct SwimmerKernel {
  static constexpr std::size_t kState = 2 * N + 2, kAction = N - 1;
  SwimmerConfig config;
  SwimmerBody body;

  template <class T>
  lanes::MaskOf<T> operator()(std::array<T, kState>& s, const std::array<T, kAction>& a,
                              T& reward) const {
    std::array<T, kAction> torque;
    for (std::size_t j = 0; j < kAction; ++j) {
      torque[j] = lanes::select(lanes::isNan(a[j]), T(0.0),
                                lanes::clamp(a[j], -config.maxTorque, config.maxTorque));
    }
    swimmer::integrateN<N, T>(body, config.integrator, config.dt / config.substeps, config.substeps,
                              s.data(), torque.data());
    reward = s[0] * config.dt;
    return lanes::noLane<T>();
  }
};

template <int N>
class SwimmerBatch final : public BatchEnvironment {
 public:
  SwimmerBatch(const Swimmer& env, BatchIsa isa)
      : BatchEnvironment(std::make_unique<Swimmer>(env.config()), isa),
        kernel_{env.config(), *env.fixedSizeBody()} {}

  void step(const BatchBuffers& io) const override {
    stepAll<SwimmerKernel<N>::kState, SwimmerKernel<N>::kAction>(kernel_, io, isa(),
                                                                 kernel_.config.horizon);
  }

 private:
  SwimmerKernel<N> kernel_;
};

using Maker = std::unique_ptr<BatchEnvironment> (*)(const Swimmer&, BatchIsa);

template <int... N>
constexpr auto makers(std::integer_sequence<int, N...>) {
  return std::array<Maker, sizeof...(N)>{
      [](const Swimmer& env, BatchIsa isa) -> std::unique_ptr<BatchEnvironment> {
        return std::make_unique<SwimmerBatch<N + 2>>(env, isa);
      }...};
}
// Entry n - 2 serves n segments.
constexpr auto kMakers = makers(std::make_integer_sequence<int, kSwimmerFixedMaxSegments - 1>{});

}  // namespace

std::unique_ptr<BatchEnvironment> makeSwimmer(const Swimmer& env, BatchIsa isa) {
  if (env.fixedSizeBody() == nullptr) return nullptr;
  return kMakers[static_cast<std::size_t>(env.segments() - 2)](env, isa);
}

}  // namespace gpfd::env::batch
