// `gpfd --plugin FILE ...`: plug-ins are loaded before the command line is parsed, so that their
// environments and learners are known to every command and listed by --help.
#pragma once

#include <vector>

namespace gpfd::app {

// Loads the plug-in of every `--plugin FILE` / `--plugin=FILE` (wherever it appears) and returns
// the other arguments, argv[0] first. InputError for a missing FILE or a plug-in that does not
// load.
std::vector<char*> loadPluginArguments(int argc, char** argv);

}  // namespace gpfd::app
