#include "gpfd/util/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gpfd/util/error.hpp"

namespace gpfd {

namespace {
constexpr const char* kTemporaryInfix = ".tmp.";
}

bool isAtomicWriteTemporary(const std::string& name) {
  const std::size_t at = name.rfind(kTemporaryInfix);
  if (at == std::string::npos || at == 0) return false;
  const std::string pid = name.substr(at + std::strlen(kTemporaryInfix));
  return !pid.empty() && pid.find_first_not_of("0123456789") == std::string::npos;
}

void writeFileAtomically(const std::string& path, const std::string& contents) {
  const std::string temporary = path + kTemporaryInfix + std::to_string(::getpid());
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(std::string("cannot write: ") + std::strerror(errno), path);
  const char* data = contents.data();
  std::size_t left = contents.size();
  int error = 0;
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      error = errno;
      break;
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  if (error == 0 && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error == 0 && std::rename(temporary.c_str(), path.c_str()) != 0) error = errno;
  if (error != 0) {
    std::remove(temporary.c_str());
    throw InputError(std::string("cannot write: ") + std::strerror(error), path);
  }
}

std::string readFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError("a directory, not a file", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(std::string("cannot read: ") + std::strerror(errno), path);
  std::ostringstream out;
  out << in.rdbuf();
  if (in.bad()) throw InputError("cannot read", path);
  return out.str();
}

void createDirectories(const std::string& dir, const std::string& what) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir, ec)) {
    const std::string why = ec ? ec.message() : "a file is in the way";
    throw InputError("cannot create the " + what + ": " + why, dir);
  }
}

}  // namespace gpfd
