// service: choosing and locking the directory a command writes its results into. One writer per
// directory (util/directory_lock.hpp), and no command ever writes over files it did not make
// unless told to (`force`).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "gpfd/util/directory_lock.hpp"

namespace gpfd::service {

// Where a request wants its results: `dir` when given (--out, out=), else a fresh
// results/<defaultName> (-2, -3, ... when taken).
struct OutputChoice {
  std::optional<std::string> dir;
  bool force = false;  // Allow a given directory that already holds files.
  std::string flag;    // How the front end names the choice in errors: "--out", "out".
};

// Checks a given directory, once locked, for what it must not hold whatever `force` says
// (InputError), e.g. a run that is to be resumed and never started over.
using DirectoryCheck = std::function<void(const std::string& dir)>;

// Locks the chosen directory. A given one must be a usable, non-empty path; `check` runs on it,
// and then, when it already holds files (holdsFiles), it is refused unless `force`, naming the
// flag. Once locked, the temporary files that a killed writer left (util/atomic_file.hpp) are
// removed, here and by lockDirectory, so that a run killed before it stored its config starts
// again with a plain restart. `defaultName` must be a plain name (the config's or the
// environment's).
DirectoryLock claimResultsDirectory(const OutputChoice& choice, const std::string& defaultName,
                                    const DirectoryCheck& check = {},
                                    const std::string& what = "results directory");

// Locks a directory that a request continues or fills in steps (a run to resume, a run of a set,
// a reproduction), creating it when missing. InputError when another process holds it.
DirectoryLock lockDirectory(const std::string& dir, const std::string& what = "results directory");

// Whether `dir` holds anything but the lock file and empty directories.
bool holdsFiles(const std::string& dir);

}  // namespace gpfd::service
