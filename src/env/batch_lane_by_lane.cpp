// env: any environment as a batch, lane by lane (makeLaneByLaneBatch, env/batch.hpp): each lane
// steps its own copy of the environment through step(), so every lane gives what the scalar
// environment gives because it is the scalar environment.
#include <memory>
#include <stdexcept>
#include <vector>

#include "batch_driver.hpp"
#include "batch_factories.hpp"

namespace gpfd::env {
namespace {

class LaneByLaneBatch final : public BatchEnvironment {
 public:
  LaneByLaneBatch(std::unique_ptr<Environment> scalar, BatchIsa isa)
      : BatchEnvironment(std::move(scalar), isa),
        space_(this->scalar().actionSpace()),
        action_(space_.components, 0.0) {}

  void reset(Rng& rng, const BatchBuffers& io, std::size_t lane) override {
    Environment& env = instance(lane);
    env.reset(rng);
    writeState(env, io, lane);
    io.elapsed[lane] = 0;
  }

  void step(const BatchBuffers& io) const override {
    if (!space_.continuous() && space_.components == 1) {
      batch::checkChoices(io, space_.choices.front(), scalar().name());
    }
    for (std::size_t l = 0; l < io.lanes; ++l) {
      Environment& env = instance(l);
      for (std::size_t c = 0; c < action_.size(); ++c) action_[c] = io.action[c * io.stride + l];
      const StepResult result = env.step(action_);
      writeState(env, io, l);
      io.reward[l] = result.reward;
      io.terminated[l] = result.terminated ? 1 : 0;
      io.truncated[l] = result.truncated ? 1 : 0;
      ++io.elapsed[l];
    }
  }

  void moveLane(std::size_t from, std::size_t to) override {
    instance(std::max(from, to));  // Both lanes exist from here on.
    std::swap(lanes_[from], lanes_[to]);
  }

 private:
  // Lane `lane`'s copy, made on first use.
  Environment& instance(std::size_t lane) const {
    if (lanes_.size() <= lane) lanes_.resize(lane + 1);
    if (!lanes_[lane]) {
      lanes_[lane] = scalar().freshCopy();
      if (!lanes_[lane]) throw std::logic_error("lane by lane: a copy of a copy failed");
    }
    return *lanes_[lane];
  }

  static void writeState(const Environment& env, const BatchBuffers& io, std::size_t lane) {
    const auto state = env.state();
    for (std::size_t i = 0; i < state.size(); ++i) io.state[i * io.stride + lane] = state[i];
  }

  ActionSpace space_;
  mutable std::vector<double> action_;                       // One lane's action.
  mutable std::vector<std::unique_ptr<Environment>> lanes_;  // Each lane's copy.
};

}  // namespace

std::unique_ptr<BatchEnvironment> makeLaneByLaneBatch(const Environment& env, BatchIsa isa) {
  auto copy = env.freshCopy();
  if (!copy) return nullptr;
  return std::make_unique<LaneByLaneBatch>(std::move(copy), batch::resolveIsa(isa));
}

}  // namespace gpfd::env
