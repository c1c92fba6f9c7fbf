#include "gpfd/util/directory_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>

#include "gpfd/util/atomic_file.hpp"
#include "gpfd/util/error.hpp"

namespace gpfd {
namespace {
namespace fs = std::filesystem;

std::string lockPath(const std::string& dir) { return dir + "/" + DirectoryLock::kFileName; }

// The pid written in an open lock file; 0 when it is not (yet) there.
long readPid(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  return n > 0 ? std::strtol(text, nullptr, 10) : 0;
}

// Whether `fd` is still the file at `path` (another process may have released and removed the
// lock file between our open and our flock).
bool sameFile(int fd, const std::string& path) {
  struct stat byFd {};
  struct stat byPath {};
  return ::fstat(fd, &byFd) == 0 && ::stat(path.c_str(), &byPath) == 0 &&
         byFd.st_dev == byPath.st_dev && byFd.st_ino == byPath.st_ino;
}

[[noreturn]] void fail(const std::string& what, int error, const std::string& dir) {
  throw InputError(what + ": " + std::strerror(error), dir);
}

bool holdsNoFile(const std::string& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
       it.increment(ec)) {
    if (!it->is_directory(ec)) return false;
  }
  return !ec;
}

}  // namespace

DirectoryLock::DirectoryLock(const std::string& dir, const std::string& what) {
  long holder = 0;
  if (!acquire(dir, what, holder)) {
    throw InputError(
        "another gpfd process (" + (holder > 0 ? "pid " + std::to_string(holder) : "pid unknown") +
            ") is writing into this directory; wait for it to end or choose another directory",
        dir);
  }
}

std::optional<DirectoryLock> DirectoryLock::tryLock(const std::string& dir,
                                                    const std::string& what) {
  DirectoryLock lock;
  long holder = 0;
  if (!lock.acquire(dir, what, holder)) return std::nullopt;
  return lock;
}

DirectoryLock DirectoryLock::lockFresh(const std::string& base, const std::string& what) {
  std::string dir = base;
  for (int n = 2;; dir = base + "-" + std::to_string(n++)) {
    std::error_code ec;
    if (fs::exists(dir, ec) || ec) {
      if (ec) throw InputError("cannot use the " + what + ": " + ec.message(), dir);
      continue;
    }
    if (auto lock = tryLock(dir, what)) {
      if (lock->created_) return std::move(*lock);
    }
  }
}

bool DirectoryLock::acquire(const std::string& dir, const std::string& what, long& holder) {
  const std::string path = lockPath(dir);
  for (int attempt = 0;; ++attempt) {
    std::error_code ec;
    const bool existed = fs::is_directory(dir, ec);
    createDirectories(dir, what);
    created_ = created_ || !existed;
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      // The directory may have been removed by a process that released it just now.
      if (errno == ENOENT && attempt < 100) continue;
      fail("cannot write the lock file " + std::string(kFileName), errno, dir);
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      if (error != EWOULDBLOCK) {
        ::close(fd);
        fail("cannot lock the directory", error, dir);
      }
      // The holder writes its pid right after locking: give it a moment.
      for (int wait = 0; wait < 50 && (holder = readPid(fd)) == 0; ++wait) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
      }
      ::close(fd);
      return false;
    }
    if (!sameFile(fd, path)) {  // Locked a lock file that its releaser removed: try again.
      ::close(fd);
      if (attempt < 100) continue;
      throw InputError("cannot lock the directory: its lock file keeps changing", dir);
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd, 0) != 0 ||
        ::pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
      const int error = errno;
      ::close(fd);
      fail("cannot write the lock file " + std::string(kFileName), error, dir);
    }
    dir_ = dir;
    fd_ = fd;
    return true;
  }
}

DirectoryLock::DirectoryLock(DirectoryLock&& other) noexcept
    : dir_(std::move(other.dir_)), fd_(other.fd_), created_(other.created_) {
  other.fd_ = -1;
}

DirectoryLock& DirectoryLock::operator=(DirectoryLock&& other) noexcept {
  if (this != &other) {
    release();
    dir_ = std::move(other.dir_);
    fd_ = other.fd_;
    created_ = other.created_;
    other.fd_ = -1;
  }
  return *this;
}

DirectoryLock::~DirectoryLock() { release(); }

void DirectoryLock::removeCreatedDirectory() {
  if (!created_) return;
  std::error_code ignored;
  for (const auto& entry : fs::directory_iterator(dir_, ignored)) {
    if (entry.path().filename() != kFileName) fs::remove_all(entry.path(), ignored);
  }
}

void DirectoryLock::release() noexcept {
  if (fd_ < 0) return;
  // Removed while still locked: a process that opened it meanwhile sees that it is gone.
  ::unlink(lockPath(dir_).c_str());
  ::close(fd_);
  fd_ = -1;
  if (created_ && holdsNoFile(dir_)) {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
}

}  // namespace gpfd
