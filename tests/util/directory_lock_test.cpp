// DirectoryLock: one holder per directory across processes; released on exit, also on a crash.
#include "gpfd/util/directory_lock.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "gpfd/util/error.hpp"

namespace gpfd {
namespace {
namespace fs = std::filesystem;

std::string fresh(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/lock-" + name;
  fs::remove_all(dir);
  return dir;
}

// In a child process: 0 when it could lock `dir`, 1 when another process holds it.
int lockInChild(const std::string& dir) {
  const pid_t pid = fork();
  if (pid == 0) _exit(DirectoryLock::tryLock(dir) ? 0 : 1);
  int status = 0;
  waitpid(pid, &status, 0);
  return WEXITSTATUS(status);
}

TEST(DirectoryLock, OneHolderAtATimeAcrossProcesses) {
  const auto dir = fresh("one");
  {
    const DirectoryLock lock(dir);
    EXPECT_TRUE(fs::is_directory(dir));
    std::ifstream file(dir + "/" + DirectoryLock::kFileName);
    long pid = 0;
    file >> pid;
    EXPECT_EQ(pid, ::getpid());
    EXPECT_EQ(lockInChild(dir), 1);
    std::ofstream(dir + "/data") << "kept";  // The directory now holds a file.
  }
  EXPECT_TRUE(fs::exists(dir + "/data"));
  EXPECT_FALSE(fs::exists(dir + "/" + DirectoryLock::kFileName));
  EXPECT_EQ(lockInChild(dir), 0);  // Released.
}

TEST(DirectoryLock, TheRefusalNamesTheHoldersPid) {
  const auto dir = fresh("pid");
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t holder = fork();
  if (holder == 0) {
    const DirectoryLock lock(dir);
    (void)!write(ready[1], "x", 1);
    pause();  // Until killed.
    _exit(0);
  }
  char byte = 0;
  ASSERT_EQ(read(ready[0], &byte, 1), 1);
  try {
    const DirectoryLock lock(dir);
    FAIL() << "locked a held directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pid " + std::to_string(holder)), std::string::npos)
        << e.message();
    EXPECT_EQ(e.where(), dir);
  }
  // A crash (SIGKILL) releases it: the kernel drops the lock with the process.
  kill(holder, SIGKILL);
  waitpid(holder, nullptr, 0);
  EXPECT_TRUE(fs::exists(dir + "/" + DirectoryLock::kFileName));  // Stale, but not locked.
  EXPECT_TRUE(DirectoryLock::tryLock(dir).has_value());
  close(ready[0]);
  close(ready[1]);
}

TEST(DirectoryLock, ADirectoryItCreatedAndNothingWroteIsRemoved) {
  const auto dir = fresh("empty");
  { const DirectoryLock lock(dir + "/sub"); }
  EXPECT_FALSE(fs::exists(dir + "/sub"));
  EXPECT_TRUE(fs::exists(dir));  // Only the directory itself, not its parents.
  {
    DirectoryLock lock(dir + "/sub");
    std::ofstream(dir + "/sub/partial") << "x";
    lock.removeCreatedDirectory();  // A command that failed before finishing.
    EXPECT_FALSE(fs::exists(dir + "/sub/partial"));
  }
  EXPECT_FALSE(fs::exists(dir + "/sub"));
  fs::create_directories(dir + "/existing");
  {
    DirectoryLock lock(dir + "/existing");
    lock.removeCreatedDirectory();  // Not created by the lock: kept.
  }
  EXPECT_TRUE(fs::exists(dir + "/existing"));
}

TEST(DirectoryLock, FreshDirectoriesSkipTakenNames) {
  const auto base = fresh("fresh");
  fs::create_directories(base);
  const DirectoryLock second = DirectoryLock::lockFresh(base);
  EXPECT_EQ(second.directory(), base + "-2");
  const DirectoryLock third = DirectoryLock::lockFresh(base);  // -2 exists (and is locked).
  EXPECT_EQ(third.directory(), base + "-3");
}

TEST(DirectoryLock, AFileInTheWayIsAnInputError) {
  const auto dir = fresh("file");
  std::ofstream(dir) << "not a directory";
  EXPECT_THROW(DirectoryLock{dir}, InputError);
  fs::remove(dir);
}

}  // namespace
}  // namespace gpfd
