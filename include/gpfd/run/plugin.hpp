// run: plug-ins, shared libraries that add environments and learners to the gpfd tool without
// rebuilding it (`gpfd --plugin libmine.so ...`, or `plugins = ["libmine.so"]` in a config).
//
// A plug-in is built against the installed package (find_package(gpfd), target gpfd::plugin: the
// headers only) and names one registration function with GPFD_PLUGIN:
//
//   void registerMine(gpfd::PluginRegistries& r) { r.environments.add(Mine::info()); }
//   GPFD_PLUGIN(registerMine)
//
// It does not link gpfd's libraries: the tool exports their symbols, and the plug-in's references
// bind to them when it is loaded, so that it registers into the tool's own registries.
// examples/mountain-car/ is a complete one.
#pragma once

#include <string>
#include <vector>

#include "gpfd/env/environment.hpp"
#include "gpfd/rl/learner.hpp"

namespace gpfd {

// Raised whenever the interfaces a plug-in sees (registries, Environment, Learner, ParamTable)
// change in a way that breaks a compiled plug-in; a plug-in built for another value is refused.
inline constexpr int kPluginAbi = 4;  // 4: ActionSpace::choices per component, legal actions.

struct PluginRegistries {
  env::Registry& environments;
  rl::LearnerRegistry& learners;
};

// Loads the plug-in at `path` (once per file; later calls with the same file do nothing) and
// lets it register. InputError naming the path when the file is missing, cannot be loaded, is not
// a gpfd plug-in, was built for another kPluginAbi, or registers a name that is taken.
void loadPlugin(const std::string& path);
// The files of the plug-ins loaded so far (absolute paths), in loading order.
std::vector<std::string> loadedPlugins();

}  // namespace gpfd

// Defines the entry points of a plug-in: `registerFunction(gpfd::PluginRegistries&)` is called
// once when the tool loads it.
#define GPFD_PLUGIN(registerFunction)                                          \
  extern "C" __attribute__((visibility("default"))) int gpfd_plugin_abi() {    \
    return ::gpfd::kPluginAbi;                                                 \
  }                                                                            \
  extern "C" __attribute__((visibility("default"))) void gpfd_plugin_register( \
      ::gpfd::PluginRegistries& registries) {                                  \
    registerFunction(registries);                                              \
  }
