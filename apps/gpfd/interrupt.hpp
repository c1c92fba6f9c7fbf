// Ctrl-C for the long commands (evolve, reproduce): the first SIGINT asks the run to stop at its
// next safe point (after a checkpoint) and says so at once; a second one ends the process at once.
#pragma once

#include <atomic>

namespace gpfd::app {

// Installs the SIGINT handler and returns the flag it sets; the run checks the flag. `notice` is
// written to stderr when the first Ctrl-C arrives (a string literal: the handler keeps it).
const std::atomic<bool>& stopOnInterrupt(const char* notice);

}  // namespace gpfd::app
