// The fibers' scheduler (fibers/scheduler.hpp): turns in index order, waits, work on the thread's
// own stack, errors, and the teardown of a schedule in which every job waits.
#include "gpfd/fibers/scheduler.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

namespace gpfd::fibers {
namespace {

TEST(FiberScheduler, AWaitThatIsReadyReturnsAtOnceAndOrderFollowsTheIndex) {
  std::vector<std::string> log;
  int arrived = 0;
  const auto errors = Scheduler::run(3, [&](std::size_t i) {
    log.push_back("start " + std::to_string(i));
    ++arrived;
    Scheduler::waitUntil([&] { return arrived == 3; });
    log.push_back("go " + std::to_string(i));
  });
  ASSERT_EQ(errors.size(), 3U);
  for (const auto& e : errors) EXPECT_EQ(e, nullptr);
  // Jobs 0 and 1 wait; job 2 finds all arrived and goes on before the others resume.
  const std::vector<std::string> expected = {"start 0", "start 1", "start 2",
                                             "go 2",    "go 0",    "go 1"};
  EXPECT_EQ(log, expected);
}

TEST(FiberScheduler, JobsRunOnFiberStacksAndOnThreadStackRunsOnTheThreadsOwn) {
  ASSERT_TRUE(onThreadsOwnStack());
  std::vector<int> onFiber, onThread, indexInRequest;
  const auto errors = Scheduler::run(2, [&](std::size_t i) {
    onFiber.push_back(onThreadsOwnStack() ? 0 : 1);
    Scheduler::onThreadStack([&] {
      onThread.push_back(onThreadsOwnStack() ? 1 : 0);
      indexInRequest.push_back(static_cast<int>(Scheduler::current()));
      EXPECT_TRUE(Scheduler::inFiber());  // The job is still the one running.
      // Nested: already on the thread's stack, so it runs in place.
      Scheduler::onThreadStack([&] { onThread.push_back(onThreadsOwnStack() ? 1 : 0); });
    });
    onFiber.push_back(onThreadsOwnStack() ? 0 : 1);
    EXPECT_EQ(Scheduler::current(), i);
  });
  for (const auto& e : errors) EXPECT_EQ(e, nullptr);
  EXPECT_EQ(onFiber, std::vector<int>(4, 1));
  EXPECT_EQ(onThread, std::vector<int>(4, 1));
  EXPECT_EQ(indexInRequest, (std::vector<int>{0, 1}));
  EXPECT_FALSE(Scheduler::inFiber());
}

TEST(FiberScheduler, OutsideAJobOnThreadStackCallsDirectlyAndTheRestRefuses) {
  bool called = false;
  Scheduler::onThreadStack([&] { called = true; });
  EXPECT_TRUE(called);
  EXPECT_THROW(Scheduler::waitUntil([] { return true; }), std::logic_error);
  EXPECT_THROW(Scheduler::current(), std::logic_error);
  EXPECT_FALSE(Scheduler::inFiber());
}

TEST(FiberScheduler, AnExceptionOnTheThreadsStackIsRethrownInTheJob) {
  std::vector<std::string> caught;
  const auto errors = Scheduler::run(2, [&](std::size_t i) {
    try {
      Scheduler::onThreadStack([&] { throw std::runtime_error("bad " + std::to_string(i)); });
    } catch (const std::runtime_error& e) {
      caught.emplace_back(e.what());
    }
  });
  for (const auto& e : errors) EXPECT_EQ(e, nullptr);
  EXPECT_EQ(caught, (std::vector<std::string>{"bad 0", "bad 1"}));
}

TEST(FiberScheduler, EachJobsErrorIsReturnedAndTheOthersFinish) {
  int finished = 0;
  const auto errors = Scheduler::run(3, [&](std::size_t i) {
    Scheduler::waitUntil([] { return true; });
    if (i == 1) throw std::runtime_error("job 1 failed");
    ++finished;
  });
  ASSERT_EQ(errors.size(), 3U);
  EXPECT_EQ(errors[0], nullptr);
  EXPECT_EQ(errors[2], nullptr);
  ASSERT_NE(errors[1], nullptr);
  EXPECT_THROW(std::rethrow_exception(errors[1]), std::runtime_error);
  EXPECT_EQ(finished, 2);
}

// Counts live objects: every suspended job's locals must be destroyed at a teardown.
struct Counted {
  explicit Counted(int& live) : live_(live) { ++live_; }
  ~Counted() { --live_; }
  Counted(const Counted&) = delete;
  Counted& operator=(const Counted&) = delete;
  int& live_;
};

TEST(FiberScheduler, ADeadlockUnwindsEverySuspendedJobThenThrows) {
  int live = 0, cancelled = 0;
  EXPECT_THROW(Scheduler::run(4,
                              [&](std::size_t) {
                                const Counted held(live);
                                std::vector<double> buffer(1000, 1.0);  // Heap: must be freed.
                                try {
                                  Scheduler::waitUntil([] { return false; });
                                } catch (const Cancelled&) {
                                  ++cancelled;
                                  // A later wait throws again: cleanup cannot wait.
                                  EXPECT_THROW(Scheduler::waitUntil([] { return true; }),
                                               Cancelled);
                                  throw;
                                }
                              }),
               std::logic_error);
  EXPECT_EQ(cancelled, 4);
  EXPECT_EQ(live, 0);
  EXPECT_FALSE(Scheduler::inFiber());
}

TEST(FiberScheduler, FibersDoNotNestAndAScheduleCanFollowAnother) {
  const auto errors = Scheduler::run(1, [](std::size_t) {
    EXPECT_THROW(Scheduler::run(1, [](std::size_t) {}), std::logic_error);
  });
  EXPECT_EQ(errors[0], nullptr);
  int ran = 0;
  (void)Scheduler::run(5, [&](std::size_t) { ++ran; });
  EXPECT_EQ(ran, 5);
  EXPECT_TRUE(Scheduler::run(0, [](std::size_t) {}).empty());
}

TEST(FiberScheduler, ADeepStackFitsInAFiber) {
  // Recursion 4 MiB deep: a fiber's stack is as large as a Linux thread's default (8 MiB).
  std::function<int(int)> deep = [&](int n) -> int {
    volatile char pad[1024] = {};
    return n == 0 ? pad[0] : deep(n - 1) + pad[n % 1024];
  };
  int result = -1;
  (void)Scheduler::run(1, [&](std::size_t) { result = deep(4000); });
  EXPECT_EQ(result, 0);
}

}  // namespace
}  // namespace gpfd::fibers
