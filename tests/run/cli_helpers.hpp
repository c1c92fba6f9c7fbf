// Running the gpfd binary from tests.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace gpfd::testing {

struct CommandResult {
  int status = -1;  // Exit code, or -1 when killed by a signal.
  std::string output;
};

// Runs gpfd with `args` in the working directory `cwd` (default: the test's).
inline CommandResult runGpfd(const std::string& args, const std::string& cwd = "") {
  CommandResult r;
  const std::string cd = cwd.empty() ? "" : "cd '" + cwd + "' && ";
  FILE* pipe = popen((cd + GPFD_BINARY + " " + args + " 2>&1").c_str(), "r");
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) {
    // A build without the JIT says so once on stderr (compiled_feature_map.cpp); the tests check
    // the rest of the output, the same in both builds.
    if (std::string_view(buffer).starts_with("gpfd: JIT unavailable")) continue;
    r.output += buffer;
  }
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A gpfd process running in the background (its own pid: sh execs it), output to a file.
struct Background {
  pid_t pid = -1;
  std::string outputFile;

  // Waits for the process; its exit code, or 128 + the signal that ended it.
  int wait() const {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
};

inline Background startGpfd(const std::string& args, const std::string& outputFile) {
  Background b{-1, outputFile};
  b.pid = fork();
  if (b.pid == 0) {
    execl(
        "/bin/sh", "sh", "-c",
        ("exec " + std::string(GPFD_BINARY) + " " + args + " > '" + outputFile + "' 2>&1").c_str(),
        static_cast<char*>(nullptr));
    _exit(127);
  }
  return b;
}

// Waits until `path` exists (true) or `seconds` passed (false).
inline bool waitForFile(const std::string& path, double seconds = 60) {
  for (int i = 0; i < seconds * 100; ++i) {
    if (std::filesystem::exists(path)) return true;
    usleep(10000);
  }
  return false;
}

inline std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Writes through a temporary file and a rename: tests run in parallel processes (ctest -j) and
// may write the same file, and a reader must never see it half-written.
inline std::string writeText(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  std::ofstream(temporary) << text;
  std::filesystem::rename(temporary, path);
  return path;
}

// A fresh, empty directory path under the test temp dir.
inline std::string freshDir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/" + name;
  std::filesystem::remove_all(dir);
  return dir;
}

// generations.csv without the wall-time column (which legitimately differs between runs).
inline std::string withoutSeconds(const std::string& csv) {
  std::stringstream in(csv), out;
  std::string line;
  while (std::getline(in, line)) out << line.substr(0, line.rfind(',')) << "\n";
  return out.str();
}

// A tiny `gpfd evolve` config (cart-pole, 12 x 6, two 4-update trials; well under a second),
// written as <name>.toml; returns its path.
inline std::string tinyEvolveConfig(const std::string& name, int seed) {
  return writeText(name + ".toml", "name = \"" + name + "\"\nseed = " + std::to_string(seed) + R"(
[env]
name = "cartpole"
params = { max_steps = 200 }
[learner]
name = "pg"
params = { updates = 4, episodes = 5 }
[fitness]
trials = 2
size_penalty = 0.001
[genome]
max_features = 4
max_depth = 4
max_size = 15
[gp]
population = 12
generations = 6
)");
}

}  // namespace gpfd::testing
