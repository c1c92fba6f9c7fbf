#include "gpfd/service/results_directory.hpp"

#include <filesystem>

#include "gpfd/util/error.hpp"

namespace gpfd::service {
namespace fs = std::filesystem;

bool holdsFiles(const std::string& dir) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    if (it->path().filename() != DirectoryLock::kFileName) return true;
  }
  return false;
}

DirectoryLock lockDirectory(const std::string& dir, const std::string& what) {
  return DirectoryLock(dir, what);
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
