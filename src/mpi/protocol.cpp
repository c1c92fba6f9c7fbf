#include "protocol.hpp"

#include <algorithm>
#include <stdexcept>
#include <thread>

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

// Per feature: its node count, then per node op (u8), var (u16), length (u32), value (f64).
Writer& Writer::putGenome(const expr::Genome& genome) {
  put(static_cast<std::uint32_t>(genome.featureCount()));
  for (std::size_t k = 0; k < genome.featureCount(); ++k) {
    const auto tree = genome.feature(k);
    put(static_cast<std::uint32_t>(tree.size()));
    for (const auto& node : tree) {
      put(static_cast<std::uint8_t>(node.op)).put(node.var).put(node.length).put(node.value);
    }
  }
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
  expr::Genome genome;
  const auto features = get<std::uint32_t>();
  for (std::uint32_t k = 0; k < features; ++k) {
    const auto size = get<std::uint32_t>();
    if (size == 0 || size > static_cast<std::uint32_t>(expr::kMaxParseSize)) {
      throw std::runtime_error("MPI message: bad feature size");
    }
    expr::Tree tree(size);
    for (auto& node : tree) {
      const auto op = get<std::uint8_t>();
      if (op >= expr::kOpCount) throw std::runtime_error("MPI message: bad opcode");
      node.op = static_cast<expr::Op>(op);
      node.var = get<std::uint16_t>();
      node.length = get<std::uint32_t>();
      node.value = get<double>();
    }
    const std::string problem = expr::checkTree(tree, variableCount);
    if (!problem.empty()) throw std::runtime_error("MPI message: bad genome: " + problem);
    genome.addFeature(tree);
  }
  return genome;
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
