// A trial runner for the tests of a time budget's timing.
#pragma once

#include <chrono>
#include <functional>
#include <limits>
#include <stdexcept>
#include <thread>
#include <vector>

#include "gpfd/run/trial_runner.hpp"

namespace gpfd::testing {

// Trains on one thread; each call after the first `fast` takes a second more. Counts its calls;
// one past `most` throws TooManyTrainings (a test that expects few ends at once where it fails).
class SlowTrialRunner final : public run::TrialRunner {
 public:
  struct TooManyTrainings : std::logic_error {
    TooManyTrainings() : std::logic_error("more trainings than the test allows") {}
  };
  explicit SlowTrialRunner(int fast = 0, int most = std::numeric_limits<int>::max())
      : fast_(fast), most_(most) {}
  std::vector<std::vector<rl::LearningCurve>> run(
      const run::LearningTask& task, const run::TrialBatch& batch,
      const std::function<void(std::size_t)>& done) override {
    if (calls == most_) throw TooManyTrainings();
    if (calls++ >= fast_) std::this_thread::sleep_for(std::chrono::seconds(1));
    return threads_.run(task, batch, done);
  }
  int calls = 0;

 private:
  int fast_;
  int most_;
  run::ThreadTrialRunner threads_{1};
};

}  // namespace gpfd::testing
