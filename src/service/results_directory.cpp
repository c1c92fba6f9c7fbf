#include "gpfd/service/results_directory.hpp"

#include <filesystem>
#include <vector>

#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd::service {
namespace fs = std::filesystem;

namespace {

// Removes the temporary files of atomic writes in `dir` and below: with the lock held, no gpfd
// process writes there, so they are what a killed writer left behind.
void removeStaleTemporaries(const std::string& dir) {
  std::error_code ec;
  std::vector<fs::path> stale;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec) && isAtomicWriteTemporary(it->path().filename().string())) {
      stale.push_back(it->path());
    }
  }
  for (const auto& path : stale) fs::remove(path, ec);
}

// Whether `dir` holds anything but the lock file and empty directories.
bool holdsFilesBelow(const fs::path& dir, bool top) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    if (top && it->path().filename() == DirectoryLock::kFileName) continue;
    if (!it->is_directory(ec) || it->is_symlink(ec) || holdsFilesBelow(it->path(), false)) {
      return true;
    }
  }
  return false;
}

}  // namespace

bool holdsFiles(const std::string& dir) { return holdsFilesBelow(dir, true); }

DirectoryLock lockDirectory(const std::string& dir, const std::string& what) {
  DirectoryLock lock(dir, what);
  removeStaleTemporaries(dir);
  return lock;
}

DirectoryLock claimResultsDirectory(const OutputChoice& choice, const std::string& defaultName,
                                    const DirectoryCheck& check, const std::string& what) {
  if (!choice.dir) return DirectoryLock::lockFresh("results/" + defaultName, what);
  const std::string& dir = *choice.dir;
  if (dir.empty()) throw InputError("an empty directory name", choice.flag + " ''");
  std::error_code ec;
  const bool existed = fs::exists(dir, ec);
  if (ec) throw InputError("cannot use the " + what + ": " + ec.message(), dir);
  if (existed && !fs::is_directory(dir, ec)) {
    throw InputError("not a directory", choice.flag + " " + dir);
  }
  DirectoryLock lock(dir, what);
  removeStaleTemporaries(dir);
  if (check) check(dir);
  if (existed && !choice.force && holdsFiles(dir)) {
    throw InputError("the directory already holds files that this command would overwrite; pass " +
                         (choice.flag == "out" ? std::string("force=True") : "--force") +
                         " to write into it anyway, or choose another " + choice.flag,
                     dir);
  }
  return lock;
}

}  // namespace gpfd::service
