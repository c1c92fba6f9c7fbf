// Cart-pole registered under another name, so that the registry gives it no batched form and the
// lockstep player steps copies of it lane by lane (env::makeLaneByLaneBatch); used by the lockstep
// tests and bench/lane_by_lane.cpp. It counts the instances made.
#pragma once

#include <atomic>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpfd/env/cartpole.hpp"
#include "gpfd/env/environment.hpp"

namespace gpfd::testing {

class UnbatchedCartPole final : public env::Environment {
 public:
  // `copyable` false: freshCopy() gives nullptr, so that not even lane by lane is possible.
  UnbatchedCartPole(std::string name, env::CartPoleConfig config, bool copyable)
      : name_(std::move(name)), inner_(config), copyable_(copyable) {
    ++made;
  }
  std::string name() const override { return name_; }
  env::Params params() const override { return inner_.params(); }
  const std::vector<std::string>& stateNames() const override { return inner_.stateNames(); }
  env::ActionSpace actionSpace() const override { return inner_.actionSpace(); }
  void reset(Rng& rng) override { inner_.reset(rng); }
  std::span<const double> state() const override { return inner_.state(); }
  void setState(std::span<const double> state) override { inner_.setState(state); }
  env::StepResult step(std::span<const double> action) override { return inner_.step(action); }
  std::unique_ptr<env::Environment> freshCopy() const override {
    return copyable_ ? env::Environment::freshCopy() : nullptr;
  }

  static inline std::atomic<int> made{0};

 private:
  std::string name_;
  env::CartPole inner_;
  bool copyable_;
};

// Registers `name` as an UnbatchedCartPole in the global registry, once.
inline void registerUnbatchedCartPole(const std::string& name, bool copyable = true) {
  auto& registry = env::Registry::global();
  if (registry.find(name) != nullptr) return;
  registry.add({name, "cart-pole without a batched form (tests, bench)",
                env::CartPoleConfig::table().specs(), [name, copyable](const Params& p) {
                  return std::make_unique<UnbatchedCartPole>(
                      name, env::CartPoleConfig::fromParams(p), copyable);
                }});
}

}  // namespace gpfd::testing
