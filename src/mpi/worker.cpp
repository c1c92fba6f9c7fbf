#include "gpfd/mpi/worker.hpp"

#include <fmt/format.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>

#include "evaluation_pool.hpp"
#include "gpfd/run/learning_task.hpp"
#include "gpfd/util/error.hpp"
#include "protocol.hpp"

namespace gpfd::mpi {
namespace {

EvaluationPool::Reply failureReply(std::uint64_t task, const std::string& host) {
  bool input = false;
  std::string what, where;
  try {
    throw;
  } catch (const InputError& e) {
    input = true;
    what = e.what();
    where = e.where();
  } catch (const std::exception& e) {
    what = e.what();
  } catch (...) {
    what = "unknown exception";
  }
  return {protocol::Failure, protocol::Writer()
                                 .put(task)
                                 .put(static_cast<std::uint8_t>(input))
                                 .putString(what)
                                 .putString(where)
                                 .putString(host)
                                 .take()};
}

void sendToMaster(const EvaluationPool::Reply& reply) {
  protocol::check(MPI_Send(reply.bytes.data(), static_cast<int>(reply.bytes.size()), MPI_BYTE,
                           protocol::kMaster, reply.tag, MPI_COMM_WORLD),
                  "MPI_Send");
}

// The learning task of the master's config, checked against this worker's build.
std::shared_ptr<const run::LearningTask> configure(const std::string& masterVersion,
                                                   const std::string& text,
                                                   const std::string& version) {
  if (masterVersion != version) {
    throw InputError("this worker runs gpfd " + version + ", the master gpfd " + masterVersion);
  }
  const auto config = run::parseExperimentConfig(text, "the master's config");
  if (run::formatExperimentConfig(config) != text) {
    throw std::runtime_error("the master's config does not read back identically here");
  }
  run::validate(config);
  return std::make_shared<const run::LearningTask>(config, run::LearningTask::Budget::Trial);
}

using Clock = std::chrono::steady_clock;

// The worker loop; throws only when the protocol itself breaks. Only this thread calls MPI; the
// pool's threads configure and evaluate. Once the master's config has come, a heartbeat goes out
// whenever nothing else was sent for the period the config names, so that the master can tell a
// worker that computes from one that is gone.
int serve(const Session& session, int threads, const std::string& version,
          const WorkerTestHooks& hooks) {
  const int count = workerThreads(session, threads);
  const std::string& host = session.host();
  // Written by the configuring job, read when a task is submitted: the master sends tasks only
  // after this worker's Ready, which the pool hands over after the write.
  std::shared_ptr<const run::LearningTask> learning;
  EvaluationPool pool(count);
  std::optional<std::chrono::milliseconds> heartbeat;
  auto lastSent = Clock::now();
  const auto send = [&](const EvaluationPool::Reply& reply) {
    sendToMaster(reply);
    lastSent = Clock::now();
  };
  // How long the loop may wait before a heartbeat is due.
  const auto untilHeartbeat = [&] {
    if (!heartbeat) return std::chrono::microseconds(std::chrono::hours(1));
    const auto left = lastSent + *heartbeat - Clock::now();
    return std::max(std::chrono::microseconds(0),
                    std::chrono::duration_cast<std::chrono::microseconds>(left));
  };
  auto pause = protocol::kMinPause;
  while (true) {
    auto replies = pool.takeReplies(std::chrono::microseconds(0));
    for (const auto& reply : replies) send(reply);
    if (!replies.empty()) pause = protocol::kMinPause;  // The next task comes soon.
    if (heartbeat && untilHeartbeat().count() == 0) send({protocol::Heartbeat, {}});

    int arrived = 0;
    MPI_Status status;
    protocol::check(MPI_Iprobe(protocol::kMaster, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status),
                    "MPI_Iprobe");
    if (!arrived && pool.pending() >= static_cast<std::size_t>(count)) {
      // Every thread is busy: nothing from the master is needed before one finishes (the master
      // sends Stop only when no task is out), so sleep until then or until a heartbeat is due.
      for (const auto& reply : pool.takeReplies(untilHeartbeat())) send(reply);
      pause = protocol::kMinPause;
      continue;
    }
    if (!arrived) {
      for (const auto& reply : pool.takeReplies(std::min(pause, untilHeartbeat()))) send(reply);
      pause = std::min(pause * 2, protocol::kMaxPause);
      continue;
    }
    pause = protocol::kMinPause;
    auto message = protocol::receive(status);
    switch (status.MPI_TAG) {
      case protocol::Stop:
        send({protocol::Stopped, {}});
        return 0;  // The master sends Stop only when no task is out.
      case protocol::Config: {
        protocol::Reader r(message);
        std::string masterVersion = r.getString(), text = r.getString();
        heartbeat = std::chrono::milliseconds(r.get<std::int64_t>());
        // Built on the pool, so that heartbeats go on while it takes.
        pool.submit([&learning, masterVersion = std::move(masterVersion), text = std::move(text),
                     &version, count, host]() -> EvaluationPool::Reply {
          try {
            learning = configure(masterVersion, text, version);
            return {protocol::Ready,
                    protocol::Writer().put(std::int32_t{count}).putString(host).take()};
          } catch (...) {
            learning.reset();
            return failureReply(protocol::kNoTask, host);
          }
        });
        break;
      }
      case protocol::Task:
        pool.submit([bytes = std::move(message), learning, &hooks, host]() {
          protocol::Reader r(bytes);
          std::uint64_t task = protocol::kNoTask;
          try {
            task = r.get<std::uint64_t>();
            if (!learning) throw std::runtime_error("a task came before the config");
            const auto seed = r.get<std::uint64_t>();
            const auto genome = r.getGenome(static_cast<int>(learning->stateDim()));
            if (hooks.beforeTask) hooks.beforeTask(task);
            Rng rng(seed);
            const double fitness = run::trialFitness(*learning, genome, rng);
            return EvaluationPool::Reply{protocol::Result,
                                         protocol::Writer().put(task).put(fitness).take()};
          } catch (...) {
            return failureReply(task, host);
          }
        });
        break;
      default:
        throw std::runtime_error(fmt::format("unexpected MPI message (tag {})", status.MPI_TAG));
    }
  }
}

}  // namespace

int workerThreads(const Session& session, int threads) {
  if (threads > 0) return threads;
  return std::max(1, tbb::info::default_concurrency() / std::max(1, session.workersOnNode()));
}

int serveAsWorker(Session& session, int threads, const std::string& version,
                  const WorkerTestHooks& hooks) {
  std::signal(SIGINT, SIG_IGN);
  try {
    return serve(session, threads, version, hooks);
  } catch (const std::exception& e) {
    // The protocol itself broke (an MPI error: most often the master is gone; a message it does
    // not know): this worker leaves without MPI_Finalize, which would wait for the others. A
    // living master takes it as lost after its timeout and goes on without it, unless mpiexec
    // ends the whole job when a process fails (hydra's default; -disable-auto-cleanup keeps it).
    std::fprintf(stderr, "error: MPI worker %d on %s: %s; leaving the MPI job\n", session.rank(),
                 session.host().c_str(), e.what());
    session.abandon();
    return 1;
  }
}

}  // namespace gpfd::mpi
