#include "evaluation_pool.hpp"

namespace gpfd::mpi {

EvaluationPool::EvaluationPool(int threads) {
  for (int t = 0; t < threads; ++t) threads_.emplace_back([this] { serve(); });
}

EvaluationPool::~EvaluationPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    jobs_.clear();
  }
  jobReady_.notify_all();
  threads_.clear();  // Joins.
}

void EvaluationPool::submit(Job job) {
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back(std::move(job));
    ++pending_;
  }
  jobReady_.notify_one();
}

std::vector<EvaluationPool::Reply> EvaluationPool::takeReplies(std::chrono::microseconds pause) {
  std::unique_lock lock(mutex_);
  replyReady_.wait_for(lock, pause, [this] { return !replies_.empty(); });
  std::vector<Reply> out;
  out.swap(replies_);
  pending_ -= out.size();
  return out;
}

std::vector<EvaluationPool::Reply> EvaluationPool::awaitReplies() {
  std::unique_lock lock(mutex_);
  replyReady_.wait(lock, [this] { return !replies_.empty(); });
  std::vector<Reply> out;
  out.swap(replies_);
  pending_ -= out.size();
  return out;
}

std::size_t EvaluationPool::pending() const {
  std::lock_guard lock(mutex_);
  return pending_;
}

void EvaluationPool::serve() {
  while (true) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      jobReady_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      if (stopping_) return;
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    Reply reply = job();
    {
      std::lock_guard lock(mutex_);
      replies_.push_back(std::move(reply));
    }
    replyReady_.notify_one();
  }
}

}  // namespace gpfd::mpi
