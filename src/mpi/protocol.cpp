#include "protocol.hpp"

#include <algorithm>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "gpfd/expr/wire.hpp"

namespace gpfd::mpi::protocol {

void check(int code, const char* call) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING] = {};
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw std::runtime_error(std::string(call) +
                           " failed: " + std::string(text, static_cast<std::size_t>(length)));
}

Writer& Writer::putString(const std::string& text) {
  put(static_cast<std::uint64_t>(text.size()));
  bytes_.insert(bytes_.end(), text.begin(), text.end());
  return *this;
}

Writer& Writer::putGenome(const expr::Genome& genome) {
  std::string record;
  expr::wire::appendGenome(record, genome);
  bytes_.insert(bytes_.end(), record.begin(), record.end());
  return *this;
}

void Reader::need(std::size_t n) const {
  if (bytes_.size() - at_ < n) throw std::runtime_error("MPI message too short");
}

std::string Reader::getString() {
  const auto size = get<std::uint64_t>();
  need(size);
  std::string text(bytes_.data() + at_, size);
  at_ += size;
  return text;
}

expr::Genome Reader::getGenome(int variableCount) {
  return expr::wire::readGenome(std::string_view(bytes_.data(), bytes_.size()), at_, variableCount);
}

std::vector<char> receive(const MPI_Status& status) {
  int count = 0;
  check(MPI_Get_count(&status, MPI_BYTE, &count), "MPI_Get_count");
  std::vector<char> bytes(static_cast<std::size_t>(count));
  check(MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE),
        "MPI_Recv");
  return bytes;
}

std::optional<MPI_Status> waitForMessage(int source, std::chrono::microseconds patience) {
  const auto until = std::chrono::steady_clock::now() + patience;
  auto pause = kMinPause;
  while (true) {
    int arrived = 0;
    MPI_Status status;
    check(MPI_Iprobe(source, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
    if (arrived) return status;
    if (std::chrono::steady_clock::now() >= until) return std::nullopt;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, kMaxPause);
  }
}

}  // namespace gpfd::mpi::protocol
