// The environment registry: names, parameter checking, resolved parameters and user environments.
#include <gtest/gtest.h>

#include <algorithm>

#include "gpfd/env/environment.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::env {
namespace {

TEST(Registry, KnowsTheBuiltInEnvironments) {
  const auto names = Registry::global().names();
  for (const char* name : {"acrobot", "cartpole", "swimmer", "tetris"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
  EXPECT_EQ(Registry::global().make("swimmer", {{"segments", "5"}})->stateDim(), 12u);
  EXPECT_EQ(Registry::global().make("tetris", {{"rows", "20"}, {"cols", "10"}})->stateDim(), 22u);
}

TEST(Registry, RejectsUnknownNamesAndParameters) {
  EXPECT_THROW(Registry::global().make("pendulum"), InputError);
  try {
    Registry::global().make("acrobot", {{"segments", "3"}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "acrobot.segments");
  }
  EXPECT_THROW(Registry::global().make("swimmer", {{"segments", "x"}}), InputError);
}

TEST(Registry, ResolvedParametersRoundTripAndMatchTheSpecs) {
  for (const auto& name : Registry::global().names()) {
    const auto& info = Registry::global().info(name);
    const auto env = Registry::global().make(name);
    const Params resolved = env->params();
    ASSERT_EQ(resolved.size(), info.params.size()) << name;
    for (const auto& spec : info.params) {
      EXPECT_EQ(resolved.at(spec.name), spec.defaultValue) << name << "." << spec.name;
      EXPECT_FALSE(spec.meaning.empty());
    }
    EXPECT_EQ(Registry::global().make(name, resolved)->params(), resolved);
    EXPECT_EQ(env->actionSpace().names.size(), env->actionSpace().components);
  }
  const Params custom{{"dt", "0.05"}, {"integrator", "euler"}, {"substeps", "4"}};
  const auto acrobot = Registry::global().make("acrobot", custom);
  EXPECT_EQ(acrobot->params().at("dt"), "0.05");
  EXPECT_EQ(acrobot->params().at("integrator"), "euler");
}

// A user environment: a point on a line that moves by its action.
class Walk final : public Environment {
 public:
  std::string name() const override { return "walk"; }
  Params params() const override { return {}; }
  const std::vector<std::string>& stateNames() const override { return names_; }
  ActionSpace actionSpace() const override {
    ActionSpace a;
    a.low = {-1};
    a.high = {1};
    a.names = {"move"};
    return a;
  }
  void reset(Rng&) override { x_[0] = 0; }
  std::span<const double> state() const override { return x_; }
  void setState(std::span<const double> s) override { x_[0] = s[0]; }
  StepResult step(std::span<const double> a) override {
    x_[0] += a[0];
    return {a[0], false, false};
  }

 private:
  std::vector<std::string> names_{"x"};
  double x_[1] = {0};
};

TEST(Registry, TakesUserEnvironmentsOnce) {
  Registry registry;
  registry.add(
      {"walk", "a point on a line", {}, [](const Params&) { return std::make_unique<Walk>(); }});
  EXPECT_THROW(
      registry.add({"walk", "again", {}, [](const Params&) { return std::make_unique<Walk>(); }}),
      InputError);
  auto env = registry.make("walk");
  Rng rng(1);
  std::vector<double> a(1);
  env->sampleAction(rng, a);
  EXPECT_GE(a[0], -1.0);
  EXPECT_LT(a[0], 1.0);
  EXPECT_EQ(env->step(a).reward, a[0]);
}

}  // namespace
}  // namespace gpfd::env
