#include "gpfd/mpi/mpi_evaluator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <list>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "gpfd/util/error.hpp"
#include "protocol.hpp"

namespace gpfd::mpi {
namespace {

// A worker's exception, as it arrived.
struct WorkerFailure {
  int rank = 0;
  bool inputError = false;
  std::string what, where, host;

  static WorkerFailure read(protocol::Reader& r, int rank) {
    WorkerFailure f;
    f.rank = rank;
    f.inputError = r.get<std::uint8_t>() != 0;
    f.what = r.getString();
    f.where = r.getString();
    f.host = r.getString();
    return f;
  }

  [[noreturn]] void raise() const {
    const std::string worker = fmt::format("MPI worker {} on {}", rank, host);
    if (inputError) throw InputError(what, where.empty() ? worker : where + "; " + worker);
    throw std::runtime_error(
        fmt::format("{} failed: {}{}", worker, what, where.empty() ? "" : " (" + where + ")"));
  }
};

// A message on its way out, with the bytes MPI_Isend reads until it completes.
struct Outgoing {
  std::vector<char> bytes;
  MPI_Request request = MPI_REQUEST_NULL;
};

// Tasks a worker may hold beyond its threads.
constexpr std::size_t kQueued = 2;

void completeFinished(std::list<Outgoing>& sending) {
  for (auto it = sending.begin(); it != sending.end();) {
    int done = 0;
    protocol::check(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "MPI_Test");
    it = done ? sending.erase(it) : std::next(it);
  }
}

}  // namespace

WorkerRelease::~WorkerRelease() {
  for (int w = 1; w < session_.size(); ++w) {
    // Errors cannot be reported from a destructor; MPI_Finalize follows anyway.
    MPI_Send(nullptr, 0, MPI_BYTE, w, protocol::Stop, MPI_COMM_WORLD);
  }
}

MpiEvaluator::MpiEvaluator(const Session& session, const std::string& configText,
                           const std::string& version, std::function<void()> onEvaluated)
    : session_(session), onEvaluated_(std::move(onEvaluated)) {
  if (!session.isMaster() || session.size() < 2) {
    throw std::logic_error("MpiEvaluator runs on rank 0 of at least 2 ranks");
  }
  auto config = protocol::Writer().putString(version).putString(configText).take();
  for (int w = 1; w < session.size(); ++w) {
    protocol::check(MPI_Send(config.data(), static_cast<int>(config.size()), MPI_BYTE, w,
                             protocol::Config, MPI_COMM_WORLD),
                    "MPI_Send");
  }
  // One reply per worker, all collected before any failure is thrown (nothing left in flight).
  credit_.assign(static_cast<std::size_t>(session.size() - 1), 0);
  std::optional<WorkerFailure> failure;
  for (int replies = 0; replies < session.size() - 1; ++replies) {
    const MPI_Status status = protocol::waitForMessage(MPI_ANY_SOURCE);
    const auto bytes = protocol::receive(status);
    protocol::Reader r(bytes);
    if (status.MPI_TAG == protocol::Ready) {
      credit_[static_cast<std::size_t>(status.MPI_SOURCE - 1)] = r.get<std::int32_t>();
    } else if (status.MPI_TAG == protocol::Failure) {
      r.get<std::uint64_t>();
      auto f = WorkerFailure::read(r, status.MPI_SOURCE);
      if (!failure) failure = std::move(f);
    } else {
      throw std::runtime_error(fmt::format("unexpected MPI message (tag {}) from rank {}",
                                           status.MPI_TAG, status.MPI_SOURCE));
    }
  }
  if (failure) failure->raise();
}

int MpiEvaluator::capacity() const { return std::accumulate(credit_.begin(), credit_.end(), 0); }

std::vector<double> MpiEvaluator::evaluate(const std::vector<const expr::Genome*>& genomes,
                                           const std::vector<std::uint64_t>& seeds) {
  const std::size_t n = genomes.size();
  std::vector<double> out(n);
  const std::uint64_t first = nextTask_;
  std::size_t next = 0;      // The next genome to send.
  std::size_t inFlight = 0;  // Tasks sent and not answered.
  std::optional<WorkerFailure> failure;
  std::list<Outgoing> sending;

  const auto send = [&](int worker) {
    const std::size_t i = next++;
    auto& message = sending.emplace_back();
    message.bytes = protocol::Writer().put(nextTask_++).put(seeds[i]).putGenome(*genomes[i]).take();
    protocol::check(MPI_Isend(message.bytes.data(), static_cast<int>(message.bytes.size()),
                              MPI_BYTE, worker, protocol::Task, MPI_COMM_WORLD, &message.request),
                    "MPI_Isend");
    --credit_[static_cast<std::size_t>(worker - 1)];
    ++inFlight;
  };

  // A worker may hold up to kQueued tasks beyond its threads (queued locally), so that it never
  // waits for the round trip to the master between tasks, even after short evaluations; one
  // more only while more than that many tasks per worker remain, so that the end of a batch
  // still spreads over all of them.
  const auto wantsAnother = [&](int worker) {
    const std::size_t perWorker = (n - next) / credit_.size();
    const int extra = static_cast<int>(std::min<std::size_t>(perWorker, kQueued));
    return next < n && credit_[static_cast<std::size_t>(worker - 1)] + extra > 0;
  };
  // Deal one task to each worker in turn while they want one, so that a short batch spreads
  // over all workers.
  for (bool dealt = true; dealt;) {
    dealt = false;
    for (int w = 1; w < session_.size(); ++w) {
      if (wantsAnother(w)) {
        send(w);
        dealt = true;
      }
    }
  }
  while (inFlight > 0) {
    const MPI_Status status = protocol::waitForMessage(MPI_ANY_SOURCE);
    const auto bytes = protocol::receive(status);
    protocol::Reader r(bytes);
    const int worker = status.MPI_SOURCE;
    if (status.MPI_TAG != protocol::Result && status.MPI_TAG != protocol::Failure) {
      throw std::runtime_error(
          fmt::format("unexpected MPI message (tag {}) from rank {}", status.MPI_TAG, worker));
    }
    const auto task = r.get<std::uint64_t>();
    if (task < first || task >= first + next) {
      throw std::runtime_error(fmt::format("MPI worker {} answered an unknown task", worker));
    }
    if (status.MPI_TAG == protocol::Result) {
      out[task - first] = r.get<double>();
      if (onEvaluated_) onEvaluated_();
    } else {
      auto f = WorkerFailure::read(r, worker);
      if (!failure) failure = std::move(f);
    }
    ++credit_[static_cast<std::size_t>(worker - 1)];
    --inFlight;
    while (!failure && wantsAnother(worker)) send(worker);
    completeFinished(sending);
  }
  for (auto& message : sending) {
    protocol::check(MPI_Wait(&message.request, MPI_STATUS_IGNORE), "MPI_Wait");
  }
  if (failure) failure->raise();
  return out;
}

}  // namespace gpfd::mpi
