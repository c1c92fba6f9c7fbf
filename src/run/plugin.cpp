#include "gpfd/run/plugin.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <mutex>

#include "gpfd/util/error.hpp"

namespace gpfd {
namespace {

std::mutex& pluginMutex() {
  static std::mutex mutex;
  return mutex;
}

std::vector<std::string>& loaded() {
  static std::vector<std::string> files;
  return files;
}

}  // namespace

void loadPlugin(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw InputError("no such plug-in file", path);
  const std::string file = fs::canonical(path, error).string();
  const std::lock_guard lock(pluginMutex());
  if (std::find(loaded().begin(), loaded().end(), file) != loaded().end()) return;

  // Never closed: the factories it registers point into it.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    throw InputError(fmt::format("cannot load the plug-in: {}", dlerror()), path);
  }
  using Abi = int (*)();
  using Register = void (*)(PluginRegistries&);
  const auto abi = reinterpret_cast<Abi>(dlsym(handle, "gpfd_plugin_abi"));
  const auto registration = reinterpret_cast<Register>(dlsym(handle, "gpfd_plugin_register"));
  if (abi == nullptr || registration == nullptr) {
    dlclose(handle);
    throw InputError("not a gpfd plug-in: it defines no GPFD_PLUGIN entry points", path);
  }
  if (abi() != kPluginAbi) {
    const int theirs = abi();
    dlclose(handle);
    throw InputError(fmt::format("the plug-in was built for plug-in ABI {}, this gpfd has {}: "
                                 "rebuild it against this gpfd",
                                 theirs, kPluginAbi),
                     path);
  }
  loaded().push_back(file);
  PluginRegistries registries{env::Registry::global(), rl::LearnerRegistry::global()};
  try {
    registration(registries);
  } catch (const InputError& e) {
    throw InputError(e.what(), path);
  }
}

std::vector<std::string> loadedPlugins() {
  const std::lock_guard lock(pluginMutex());
  return loaded();
}

}  // namespace gpfd
