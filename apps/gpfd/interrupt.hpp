// Ctrl-C for the long commands (evolve, reproduce): the first SIGINT asks the run to stop at its
// next safe point (after a checkpoint); a second one ends the process at once.
#pragma once

#include <atomic>

namespace gpfd::app {

// Installs the SIGINT handler and returns the flag it sets; the run checks the flag.
const std::atomic<bool>& stopOnInterrupt();

}  // namespace gpfd::app
