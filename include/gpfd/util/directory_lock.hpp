// util: an exclusive lock on a results directory, so that two gpfd processes never write into the
// same one (their files would mix). It is an advisory flock(2) on DIR/.gpfd.lock, which holds the
// owner's pid: the kernel drops it when the process ends, also on a crash or SIGKILL, so a stale
// lock file never blocks a later run.
#pragma once

#include <optional>
#include <string>

namespace gpfd {

class DirectoryLock {
 public:
  // The lock file's name inside a locked directory.
  static constexpr const char* kFileName = ".gpfd.lock";

  // Locks `dir`, creating it (and its parents) when missing. Throws InputError (where: dir) when
  // another process holds the lock, naming that process's pid, or when the directory cannot be
  // created ("cannot create the `what`") or the lock file written.
  explicit DirectoryLock(const std::string& dir, const std::string& what = "output directory");
  // The same, but nullopt instead of an InputError when another process holds the lock.
  static std::optional<DirectoryLock> tryLock(const std::string& dir,
                                              const std::string& what = "output directory");
  // Locks a new directory: `base`, or `base`-2, -3, ... when taken (existing, or just locked by
  // another process), so that running a command again never writes into an earlier run's files.
  static DirectoryLock lockFresh(const std::string& base,
                                 const std::string& what = "output directory");

  DirectoryLock(DirectoryLock&& other) noexcept;
  DirectoryLock& operator=(DirectoryLock&& other) noexcept;
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;
  // Releases the lock and removes the lock file. A directory that this lock created and that
  // holds no file when released (nothing was written: the command failed on bad input) is
  // removed as well.
  ~DirectoryLock();

  const std::string& directory() const { return dir_; }
  // For a command that failed before writing anything worth keeping: when this lock created the
  // directory, empties it (the lock file stays until the release, which then removes the
  // directory); otherwise does nothing.
  void removeCreatedDirectory();

 private:
  DirectoryLock() = default;
  // Locks or returns false when another process holds the lock (its pid in `holder`, 0 when
  // unknown); InputError for other failures.
  bool acquire(const std::string& dir, const std::string& what, long& holder);
  void release() noexcept;

  std::string dir_;
  int fd_ = -1;
  bool created_ = false;
};

}  // namespace gpfd
