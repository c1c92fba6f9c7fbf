// mpi (private): a worker's fixed set of threads that evaluate the tasks its MPI thread hands
// them and queue the replies for that thread to send (only the MPI thread calls MPI).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace gpfd::mpi {

class EvaluationPool {
 public:
  // A reply: the message's tag and bytes.
  struct Reply {
    int tag = 0;
    std::vector<char> bytes;
  };
  using Job = std::function<Reply()>;  // Must not throw.

  explicit EvaluationPool(int threads);
  ~EvaluationPool();  // Finishes the jobs already started, drops the queued ones.
  EvaluationPool(const EvaluationPool&) = delete;
  EvaluationPool& operator=(const EvaluationPool&) = delete;

  void submit(Job job);
  // Waits up to `pause` for at least one reply, then returns every reply ready (maybe none).
  std::vector<Reply> takeReplies(std::chrono::microseconds pause);
  // Waits until at least one reply is ready (some job must be pending), then returns them all.
  std::vector<Reply> awaitReplies();
  // Jobs submitted whose replies were not taken yet.
  std::size_t pending() const;

 private:
  void serve();

  mutable std::mutex mutex_;
  std::condition_variable jobReady_, replyReady_;
  std::deque<Job> jobs_;
  std::vector<Reply> replies_;
  std::size_t pending_ = 0;
  bool stopping_ = false;
  std::vector<std::jthread> threads_;
};

}  // namespace gpfd::mpi
