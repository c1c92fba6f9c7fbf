#include "gpfd/mpi/mpi_evaluator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>
#include <unordered_map>

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

// Tasks a worker may hold beyond its threads.
constexpr std::size_t kQueued = 2;

// How long one wait for a message lasts before the master looks at its sends and at silent
// workers again.
constexpr std::chrono::milliseconds kPollWindow{20};

[[noreturn]] void unexpected(int tag, int rank) {
  throw std::runtime_error(fmt::format("unexpected MPI message (tag {}) from rank {}", tag, rank));
}

std::string seconds(std::chrono::milliseconds d) {
  return fmt::format("{:g} s", std::chrono::duration<double>(d).count());
}

}  // namespace

WorkerRelease::~WorkerRelease() {
  // Errors cannot be reported from a destructor: a worker that does not answer is lost, and
  // the session ends the job with MPI_Abort.
  using Clock = std::chrono::steady_clock;
  std::map<int, Clock::time_point> waiting;  // Rank -> last heard from.
  for (int w = 1; w < session_.size(); ++w) {
    if (session_.isLost(w)) continue;
    // A 0-byte message is sent eagerly: MPI_Send returns at once even to a stopped worker.
    if (MPI_Send(nullptr, 0, MPI_BYTE, w, protocol::Stop, MPI_COMM_WORLD) == MPI_SUCCESS) {
      waiting[w] = Clock::now();
    } else {
      session_.markLost(w);
    }
  }
  // Each worker answers Stopped after whatever it still had to send (results, heartbeats); one
  // silent for the timeout is lost.
  try {
    while (!waiting.empty()) {
      if (const auto status = protocol::waitForMessage(MPI_ANY_SOURCE, kPollWindow)) {
        protocol::receive(*status);
        const auto it = waiting.find(status->MPI_SOURCE);
        if (it != waiting.end()) it->second = Clock::now();
        if (it != waiting.end() && status->MPI_TAG == protocol::Stopped) waiting.erase(it);
      }
      for (auto it = waiting.begin(); it != waiting.end();) {
        if (Clock::now() - it->second <= timeout_) {
          ++it;
          continue;
        }
        session_.markLost(it->first);
        it = waiting.erase(it);
      }
    }
  } catch (const std::exception&) {
    for (const auto& [rank, heard] : waiting) session_.markLost(rank);
  }
}

MpiEvaluator::MpiEvaluator(Session& session, const std::string& configText,
                           const std::string& version, MpiEvaluatorOptions options)
    : session_(session), options_(std::move(options)) {
  if (!session.isMaster() || session.size() < 2) {
    throw std::logic_error("MpiEvaluator runs on rank 0 of at least 2 ranks");
  }
  const auto heartbeat = std::max<std::int64_t>(1, options_.workerTimeout.count() / 10);
  const auto config =
      protocol::Writer().putString(version).putString(configText).put(heartbeat).take();
  const auto now = Clock::now();
  std::set<int> waiting;
  for (int w = 1; w < session.size(); ++w) {
    if (session.isLost(w)) continue;
    workers_[w].heard = now;
    waiting.insert(w);
    post(w, protocol::Config, config);
  }
  // One reply per worker, all collected before any failure is thrown (nothing left in flight).
  std::optional<WorkerFailure> failure;
  while (!waiting.empty()) {
    if (const auto status = protocol::waitForMessage(MPI_ANY_SOURCE, kPollWindow)) {
      const auto bytes = protocol::receive(*status);
      const int w = status->MPI_SOURCE;
      if (!workers_.contains(w)) continue;  // A lost worker's: dropped.
      workers_[w].heard = Clock::now();
      protocol::Reader r(bytes);
      if (status->MPI_TAG == protocol::Ready) {
        workers_[w].credit = r.get<std::int32_t>();
        workers_[w].host = r.getString();
        waiting.erase(w);
      } else if (status->MPI_TAG == protocol::Failure) {
        r.get<std::uint64_t>();
        auto f = WorkerFailure::read(r, w);
        if (!failure) failure = std::move(f);
        waiting.erase(w);
      } else if (status->MPI_TAG != protocol::Heartbeat) {
        unexpected(status->MPI_TAG, w);
      }
    }
    testSends();
    loseSilent();
    for (auto it = waiting.begin(); it != waiting.end();) {
      it = workers_.contains(*it) ? std::next(it) : waiting.erase(it);
    }
  }
  if (failure) failure->raise();
  if (workers_.empty()) throw std::runtime_error("every MPI worker was lost");
}

int MpiEvaluator::workers() const { return static_cast<int>(workers_.size()); }

void MpiEvaluator::post(int rank, int tag, std::vector<char> bytes) {
  auto& message = sending_.emplace_back();
  message.rank = rank;
  message.bytes = std::move(bytes);
  const int code = MPI_Isend(message.bytes.data(), static_cast<int>(message.bytes.size()), MPI_BYTE,
                             rank, tag, MPI_COMM_WORLD, &message.request);
  if (code != MPI_SUCCESS) {
    sending_.pop_back();
    lose(rank, "a send to it failed");
  }
}

void MpiEvaluator::testSends() {
  for (auto it = sending_.begin(); it != sending_.end();) {
    if (!workers_.contains(it->rank)) {
      ++it;  // Never awaited: the worker may never take it.
      continue;
    }
    int done = 0;
    if (MPI_Test(&it->request, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS) {
      const int rank = it->rank;
      it = sending_.erase(it);  // MPI has finished with the request: it failed.
      lose(rank, "a send to it failed");
      continue;
    }
    it = done ? sending_.erase(it) : std::next(it);
  }
}

void MpiEvaluator::loseSilent() {
  const auto now = Clock::now();
  std::vector<int> silent;
  for (const auto& [rank, worker] : workers_) {
    if (now - worker.heard > options_.workerTimeout) silent.push_back(rank);
  }
  for (const int rank : silent) {
    lose(rank, "no message from it for " + seconds(options_.workerTimeout));
  }
}

void MpiEvaluator::lose(int rank, const std::string& why) {
  const auto it = workers_.find(rank);
  if (it == workers_.end()) return;
  const std::size_t tasks = it->second.tasks.size();
  const std::string host = it->second.host.empty() ? "" : " on " + it->second.host;
  orphans_.insert(orphans_.end(), it->second.tasks.begin(), it->second.tasks.end());
  workers_.erase(it);
  session_.markLost(rank);
  if (options_.onWorkerLost) {
    options_.onWorkerLost(
        fmt::format("MPI worker {}{} lost ({}); the {} evaluation(s) it held go to the {} "
                    "other worker(s)",
                    rank, host, why, tasks, workers_.size()));
  }
}

std::vector<double> MpiEvaluator::evaluate(const std::vector<const expr::Genome*>& genomes,
                                           const std::vector<std::uint64_t>& seeds) {
  const std::size_t n = genomes.size();
  std::vector<double> out(n);
  std::vector<bool> done(n, false);
  std::size_t remaining = n;
  std::deque<std::size_t> queue;  // Genomes to send: those of lost workers first.
  for (std::size_t i = 0; i < n; ++i) queue.push_back(i);
  std::unordered_map<std::uint64_t, std::size_t> genomeOf;  // Task number -> genome.
  std::optional<WorkerFailure> failure;
  // The master did not listen between batches: every worker starts with a full timeout.
  for (auto& [rank, worker] : workers_) worker.heard = Clock::now();

  const auto send = [&](int rank) {
    const std::size_t i = queue.front();
    queue.pop_front();
    const std::uint64_t task = nextTask_++;
    genomeOf[task] = i;
    auto& worker = workers_.at(rank);
    worker.tasks.push_back(task);
    --worker.credit;
    post(rank, protocol::Task,
         protocol::Writer().put(task).put(seeds[i]).putGenome(*genomes[i]).take());
  };
  // A worker may hold up to kQueued tasks beyond its threads (queued locally), so that it never
  // waits for the round trip to the master between tasks, even after short evaluations; one
  // more only while more than that many tasks per worker remain, so that the end of a batch
  // still spreads over all of them.
  const auto wantsAnother = [&](int rank) {
    const auto it = workers_.find(rank);
    if (failure || queue.empty() || it == workers_.end()) return false;
    const std::size_t perWorker = queue.size() / workers_.size();
    const int extra = static_cast<int>(std::min<std::size_t>(perWorker, kQueued));
    return it->second.credit + extra > 0;
  };
  // Deals one task to each worker in turn while they want one, so that a short batch spreads
  // over all workers.
  const auto deal = [&] {
    for (bool dealt = true; dealt;) {
      dealt = false;
      for (int w = 1; w < session_.size(); ++w) {
        if (wantsAnother(w)) {
          send(w);
          dealt = true;
        }
      }
    }
  };
  const auto outstanding = [&] {
    std::size_t count = 0;
    for (const auto& [rank, worker] : workers_) count += worker.tasks.size();
    return count;
  };
  // Tasks of lost workers go back to the front of the queue (unless already answered).
  const auto reclaim = [&] {
    for (const std::uint64_t task : orphans_) {
      const std::size_t i = genomeOf.at(task);
      genomeOf.erase(task);
      if (!done[i]) queue.push_front(i);
    }
    orphans_.clear();
  };

  deal();
  while (failure ? outstanding() > 0 : remaining > 0) {
    if (workers_.empty()) {
      throw std::runtime_error(
          fmt::format("every MPI worker was lost, with {} of the generation's {} evaluations left",
                      remaining, n));
    }
    if (const auto status = protocol::waitForMessage(MPI_ANY_SOURCE, kPollWindow)) {
      const auto bytes = protocol::receive(*status);
      const int rank = status->MPI_SOURCE;
      const int tag = status->MPI_TAG;
      const auto it = workers_.find(rank);
      if (it != workers_.end()) {  // Else a lost worker's message: dropped.
        auto& worker = it->second;
        worker.heard = Clock::now();
        if (tag == protocol::Result || tag == protocol::Failure) {
          protocol::Reader r(bytes);
          const auto task = r.get<std::uint64_t>();
          const auto held = std::find(worker.tasks.begin(), worker.tasks.end(), task);
          if (held == worker.tasks.end()) {
            throw std::runtime_error(fmt::format("MPI worker {} answered an unknown task", rank));
          }
          worker.tasks.erase(held);
          ++worker.credit;
          const std::size_t i = genomeOf.at(task);
          genomeOf.erase(task);
          if (tag == protocol::Result) {
            out[i] = r.get<double>();
            if (!done[i]) {
              done[i] = true;
              --remaining;
              if (options_.onEvaluated) options_.onEvaluated();
            }
          } else {
            auto f = WorkerFailure::read(r, rank);
            if (!failure) failure = std::move(f);
          }
        } else if (tag != protocol::Heartbeat) {
          unexpected(tag, rank);
        }
      }
    }
    testSends();
    loseSilent();
    reclaim();
    deal();
  }
  // Every send to a living worker was taken (it answered): they complete now.
  while (std::any_of(sending_.begin(), sending_.end(),
                     [&](const Outgoing& m) { return workers_.contains(m.rank); })) {
    std::this_thread::sleep_for(protocol::kMinPause);
    testSends();
    loseSilent();
  }
  orphans_.clear();
  if (failure) failure->raise();
  return out;
}

}  // namespace gpfd::mpi
