// mpi (private): the master/worker messages. Every message is a flat byte buffer sent as MPI_BYTE
// on MPI_COMM_WORLD; its tag says what it is. The master is rank 0.
//
//   master -> worker  Config    version, resolved config (TOML text), heartbeat period (ms)
//   worker -> master  Ready     credit: how many tasks it evaluates at once (threads), host
//   master -> worker  Task      task number, seed, genome (gpfd/expr/wire.hpp's record)
//   worker -> master  Result    task number, fitness
//   worker -> master  Failure   task number (kNoTask for setup), input error?, what, where, host
//   worker -> master  Heartbeat (empty): sent when nothing else was sent for a heartbeat period
//   master -> worker  Stop      (empty): leave the worker loop
//   worker -> master  Stopped   (empty): the worker's last message
//
// A worker sends one Result or Failure per Task it received: the reply is also its request for
// the next task (dynamic load balancing). A worker the master has not heard from for its
// timeout is lost to it: the master never sends to it again and drops what it still sends.
#pragma once

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "gpfd/expr/genome.hpp"

namespace gpfd::mpi::protocol {

enum Tag : int {
  Config = 1,
  Ready = 2,
  Task = 3,
  Result = 4,
  Failure = 5,
  Stop = 6,
  Heartbeat = 7,
  Stopped = 8
};

inline constexpr std::uint64_t kNoTask = ~std::uint64_t{0};
inline constexpr int kMaster = 0;

// Throws std::runtime_error naming `call` when an MPI call did not return MPI_SUCCESS.
void check(int code, const char* call);

// Appends plain values and strings to a byte buffer.
class Writer {
 public:
  template <typename T>
  Writer& put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    // resize + memcpy, not insert(end, p, p + n): GCC 12 -O3 reports a false
    // -Wstringop-overflow (a write into a region of size 0) for the inlined insert.
    const std::size_t at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, &value, sizeof(T));
    return *this;
  }
  Writer& putString(const std::string& text);
  // The genome's record in the one wire format (gpfd/expr/wire.hpp).
  Writer& putGenome(const expr::Genome& genome);
  std::vector<char> take() { return std::move(bytes_); }

 private:
  std::vector<char> bytes_;
};

// Reads what a Writer wrote; throws std::runtime_error on a short or malformed message.
class Reader {
 public:
  explicit Reader(const std::vector<char>& bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string getString();
  // The genome (expr::wire::readGenome), checked: well-formed trees over `variableCount`
  // variables; expr::wire::WireError when the record is truncated, corrupt or of another version.
  expr::Genome getGenome(int variableCount);

 private:
  void need(std::size_t n) const;
  const std::vector<char>& bytes_;
  std::size_t at_ = 0;
};

// Receives the message that `status` (from MPI_Probe/MPI_Iprobe) announced.
std::vector<char> receive(const MPI_Status& status);

// Polls for a message from `source` (or MPI_ANY_SOURCE) for at most `patience`, with a growing
// sleep between polls (MPICH's blocking calls spin, which would steal a core from the computing
// ranks); nothing when none came.
std::optional<MPI_Status> waitForMessage(int source, std::chrono::microseconds patience);

// Sleep between polls: from kMinPause, doubling up to kMaxPause while nothing arrives. The
// queued tasks of each worker (mpi_evaluator.cpp) hide this latency when evaluations take
// longer than kMaxPause; shorter pauses cost CPU in every idle process.
inline constexpr std::chrono::microseconds kMinPause{10};
inline constexpr std::chrono::microseconds kMaxPause{1000};

}  // namespace gpfd::mpi::protocol
