// A program of one's own linked with gpfd::core (not a plug-in): it registers the mountain car
// of mountain_car.cpp, compiled in, through the plug-in's entry point, and trains policy gradient
// on its raw state variables through the registries, with mountain-car.toml's learner (20 updates
// of 50 episodes, std 1, inputs normalised online) and the car's defaults (started anywhere, 200
// steps at most). Seed 1: mean return -145 at update 0, -64 at update 20 (README.md).
#include <cstdio>

#include "gpfd/env/environment.hpp"
#include "gpfd/features/feature_map.hpp"
#include "gpfd/rl/learner.hpp"
#include "gpfd/run/plugin.hpp"

extern "C" void gpfd_plugin_register(gpfd::PluginRegistries& registries);

int main() {
  using namespace gpfd;
  PluginRegistries registries{env::Registry::global(), rl::LearnerRegistry::global()};
  gpfd_plugin_register(registries);
  const auto car = env::Registry::global().make("mountain-car", {});
  const auto learner = rl::LearnerRegistry::global().make(
      "pg", {{"updates", "20"}, {"episodes", "50"}, {"std", "1"}, {"normalise", "true"}});
  const features::RawFeatureMap state(car->stateDim());
  Rng rng(1);
  const rl::LearningCurve curve = learner->train(*car, state, rng);
  for (const auto& p : curve.points) {
    std::printf("update %d: %lld episodes, mean return %g\n", p.update,
                static_cast<long long>(p.episodes), p.meanReturn);
  }
  // scripts/check-plugin-example runs this: it fails unless the learner improved.
  const bool learned = curve.points.size() == 21 && !curve.diverged &&
                       curve.points.back().meanReturn > curve.points.front().meanReturn;
  return learned ? 0 : 1;
}
