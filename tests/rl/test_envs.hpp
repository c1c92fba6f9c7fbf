// Tiny environments for the learner tests (no real benchmark needed).
#pragma once

#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"

namespace gpfd::rl::testing {

// A one-step linear-Gaussian bandit: state s ~ U(-1, 1); continuous action a in [-1, 1] (not
// clipped, so the return is smooth in the action); reward offset - (a - slope * s)^2.
class LinearBandit final : public env::Environment {
 public:
  explicit LinearBandit(double slope = 1.0, double offset = 0.0) : slope_(slope), offset_(offset) {}
  std::string name() const override { return "linear-bandit"; }
  env::Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  env::ActionSpace actionSpace() const override {
    env::ActionSpace space;
    space.kind = env::ActionSpace::Kind::Continuous;
    space.low = {-1.0};
    space.high = {1.0};
    return space;
  }
  void reset(Rng& rng) override { s_ = rng.uniform(-1.0, 1.0); }
  std::span<const double> state() const override { return {&s_, 1}; }
  void setState(std::span<const double> state) override { s_ = state[0]; }
  env::StepResult step(std::span<const double> action) override {
    const double err = action[0] - slope_ * s_;
    return {offset_ - err * err, true, false};
  }
  // Exact expected return of a ~ N(w0 s + w1, sd^2): offset - ((w0 - slope)^2 / 3 + w1^2) - sd^2.
  double expectedReturn(double w0, double w1, double sd) const {
    return offset_ - ((w0 - slope_) * (w0 - slope_) / 3.0 + w1 * w1) - sd * sd;
  }

 private:
  double slope_, offset_;
  double s_ = 0.0;
  std::vector<std::string> names_{"s"};
};

// A discrete corridor: position in {0..length}, start at 0, actions {left, right}; reward -1 per
// step until the right end (terminal), time limit `limit`. A learner must learn to go right.
class Corridor final : public env::Environment {
 public:
  explicit Corridor(int length = 5, int limit = 50) : length_(length), limit_(limit) {}
  std::string name() const override { return "corridor"; }
  env::Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  env::ActionSpace actionSpace() const override {
    env::ActionSpace space;
    space.kind = env::ActionSpace::Kind::Discrete;
    space.choices = {2};
    return space;
  }
  void reset(Rng&) override {
    x_ = 0.0;
    t_ = 0;
  }
  std::span<const double> state() const override { return {&x_, 1}; }
  void setState(std::span<const double> state) override { x_ = state[0]; }
  env::StepResult step(std::span<const double> action) override {
    x_ = std::max(0.0, x_ + (action[0] > 0.5 ? 1.0 : -1.0));
    ++t_;
    const bool done = x_ >= length_;
    return {done ? 0.0 : -1.0, done, !done && t_ >= limit_};
  }

 private:
  int length_, limit_;
  double x_ = 0.0;
  int t_ = 0;
  std::vector<std::string> names_{"x"};
};

// An environment whose state turns to NaN after a few steps.
class PoisonedEnv final : public env::Environment {
 public:
  std::string name() const override { return "poisoned"; }
  env::Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  env::ActionSpace actionSpace() const override {
    env::ActionSpace space;
    space.low = {-1.0};
    space.high = {1.0};
    return space;
  }
  void reset(Rng&) override { t_ = 0, s_ = 0.0; }
  std::span<const double> state() const override { return {&s_, 1}; }
  void setState(std::span<const double> state) override { s_ = state[0]; }
  env::StepResult step(std::span<const double>) override {
    ++t_;
    if (t_ > 3) s_ = std::numeric_limits<double>::quiet_NaN();
    return {1.0, false, t_ >= 10};
  }

 private:
  int t_ = 0;
  double s_ = 0.0;
  std::vector<std::string> names_{"s"};
};

}  // namespace gpfd::rl::testing
