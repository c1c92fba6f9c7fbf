// util: writing files so that a reader never sees a half-written one.
#pragma once

#include <string>

namespace gpfd {

// Writes `contents` to `path` through a temporary file in the same directory, flushed and then
// renamed over `path`. Throws InputError naming the path when any step fails (unwritable
// directory, full disk); the temporary file is removed and `path` is left as it was.
void writeFileAtomically(const std::string& path, const std::string& contents);
// Whether `name` (a file name) is one of writeFileAtomically's temporary files (`NAME.tmp.PID`),
// left behind only when the writer was killed mid-write.
bool isAtomicWriteTemporary(const std::string& name);

// The whole file; throws InputError naming the path when it cannot be read.
std::string readFile(const std::string& path);

// Creates `dir` and its parents where missing; throws InputError "cannot create the `what`"
// naming it when that fails or when `dir` exists as something other than a directory.
void createDirectories(const std::string& dir, const std::string& what = "output directory");

}  // namespace gpfd
