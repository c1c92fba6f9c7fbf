// service: what a request may ask of this machine: threads and memory.
#pragma once

#include <string>

namespace gpfd::service {

// The number of worker threads to use: `requested` (0: all cores), or the number of cores when
// it asks for more (with a note on stderr once), since more threads than cores only add overhead.
int usableThreads(int requested);

// Refuses, as an InputError at `where`, work that would hold more than this machine's physical
// memory: `bytes` is the estimate of what `what` keeps in memory.
void requireMemory(double bytes, const std::string& what, const std::string& where);

}  // namespace gpfd::service
