// util: writing files so that a reader never sees a half-written one.
#pragma once

#include <string>

namespace gpfd {

// Writes `contents` to `path` through a temporary file in the same directory, flushed and then
// renamed over `path`. Throws InputError naming the path when any step fails (unwritable
// directory, full disk); the temporary file is removed and `path` is left as it was.
void writeFileAtomically(const std::string& path, const std::string& contents);

// The whole file; throws InputError naming the path when it cannot be read.
std::string readFile(const std::string& path);

}  // namespace gpfd
