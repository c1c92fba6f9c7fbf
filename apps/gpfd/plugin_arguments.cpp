#include "plugin_arguments.hpp"

#include <string_view>

#include "gpfd/run/plugin.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::app {

std::vector<char*> loadPluginArguments(int argc, char** argv) {
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (i > 0 && arg == "--plugin") {
      if (i + 1 >= argc) throw InputError("--plugin needs a file", "--plugin");
      loadPlugin(argv[++i]);
    } else if (i > 0 && arg.starts_with("--plugin=")) {
      loadPlugin(std::string(arg.substr(9)));
    } else {
      rest.push_back(argv[i]);
    }
  }
  return rest;
}

}  // namespace gpfd::app
