// A program of one's own linked with gpfd::core (not a plug-in): it registers the mountain car
// of mountain_car.cpp, compiled in, through the plug-in's entry point, and trains policy gradient
// on its raw state variables through the registries.
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
  const auto car = env::Registry::global().make("mountain-car", {{"max_steps", "300"}});
  const auto learner = rl::LearnerRegistry::global().make("pg", {{"updates", "5"}, {"std", "1"}});
  const features::RawFeatureMap state(car->stateDim());
  Rng rng(1);
  const rl::LearningCurve curve = learner->train(*car, state, rng);
  for (const auto& p : curve.points) {
    std::printf("update %d: %lld episodes, mean return %g\n", p.update,
                static_cast<long long>(p.episodes), p.meanReturn);
  }
  return curve.points.size() == 6 ? 0 : 1;
}
