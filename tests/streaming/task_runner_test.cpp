// core/task_runner.h and core/clock.h as the streaming stack uses them (ThreadPool,
// ManualTaskRunner, ManualClock), and core's parallelFor over a runner: what runs where and
// when, the destructor's drain, long-running tasks, first error wins. Waits are on conditions.

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <future>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "core/capped_runner.h"
#include "core/clock.h"
#include "core/task_runner.h"
#include "core/parallel_for.h"

namespace vegstream {
namespace {

// Counts calls and lets a test wait for a number of them.
struct Counter {
  std::mutex mu;
  std::condition_variable cv;
  int n = 0;
  void hit() {
    std::lock_guard lock(mu);
    ++n;
    cv.notify_all();
  }
  bool waitFor(int count) {
    std::unique_lock lock(mu);
    return cv.wait_for(lock, std::chrono::seconds(10), [&] { return n >= count; });
  }
};

TEST(ManualTaskRunner, RunsNothingUntilToldThenInOrderIncludingWhatTasksPost) {
  ManualTaskRunner tasks;
  std::vector<int> order;
  tasks.post([&] { order.push_back(1); });
  tasks.post([&] {
    order.push_back(2);
    tasks.post([&] { order.push_back(4); });
  });
  tasks.postLongRunning([&] { order.push_back(3); });
  EXPECT_TRUE(order.empty());
  EXPECT_EQ(tasks.pending(), 3u);
  EXPECT_TRUE(tasks.runOne());
  EXPECT_EQ(order, (std::vector<int>{1}));
  EXPECT_EQ(tasks.runAll(), 3u);
  EXPECT_EQ(order, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_FALSE(tasks.runOne());
  EXPECT_EQ(tasks.concurrency(), 1);
}

TEST(ThreadPool, RunsEveryTaskOnItsWorkersAndTheDestructorRunsWhatIsQueued) {
  Counter done;
  std::set<std::thread::id> threads;
  std::mutex mu;
  {
    ThreadPool pool(3);
    EXPECT_EQ(pool.concurrency(), 3);
    for (int i = 0; i < 200; ++i)
      pool.post([&] {
        {
          std::lock_guard lock(mu);
          threads.insert(std::this_thread::get_id());
        }
        done.hit();
      });
    EXPECT_TRUE(done.waitFor(100));
  }  // the rest run before the destructor returns
  EXPECT_EQ(done.n, 200);
  EXPECT_EQ(threads.count(std::this_thread::get_id()), 0u) << "never on the posting thread";
  EXPECT_LE(threads.size(), 3u);
}

// A long-running task (a loop waiting for its stop signal) has a thread of its own: on a pool of
// one worker, posted tasks still run while it loops.
TEST(ThreadPool, ALongRunningTaskDoesNotHoldBackPostedOnes) {
  std::promise<void> stop;
  std::shared_future<void> stopped = stop.get_future().share();
  Counter loops, posted;
  ThreadPool pool(1);
  pool.postLongRunning([&, stopped] {
    loops.hit();
    stopped.wait();
  });
  ASSERT_TRUE(loops.waitFor(1));
  for (int i = 0; i < 5; ++i) pool.post([&] { posted.hit(); });
  EXPECT_TRUE(posted.waitFor(5));
  stop.set_value();  // the owner stops its loop before the pool goes
}

TEST(ManualClock, IsWhatTheTestSetsAndSteadyClockMovesForward) {
  ManualClock manual(5.0);
  const Clock& clock = manual;
  EXPECT_EQ(clock.nowS(), 5.0);
  manual.advance(0.25);
  EXPECT_EQ(clock.nowS(), 5.25);
  manual.set(10.0);
  EXPECT_EQ(clock.nowS(), 10.0);
  SteadyClock steady;
  const double a = steady.nowS();
  EXPECT_GE(a, 0.0);
  EXPECT_GE(steady.nowS(), a);
}

// With a runner that never runs anything, the calling thread does all the work; helpers posted
// and run afterwards find the loop closed and touch nothing.
TEST(ParallelFor, OnAManualRunnerTheCallerDoesEveryIndexOnce) {
  ManualTaskRunner tasks;
  std::vector<int> seen(50, 0);
  const Status s = parallelFor(seen.size(), 4, &tasks, [&](size_t i) -> Status {
    ++seen[i];
    return {};
  });
  EXPECT_TRUE(s);
  EXPECT_EQ(tasks.pending(), 3u) << "threads 4: three helpers posted beside the caller";
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << i;
  EXPECT_EQ(tasks.runAll(), 3u);
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << i;
}

TEST(ParallelFor, OnAPoolEveryIndexRunsOnceAndTheFirstErrorIsReturned) {
  ThreadPool pool(3);
  std::vector<std::atomic<int>> seen(500);
  EXPECT_TRUE(parallelFor(seen.size(), 0, &pool, [&](size_t i) -> Status {
    seen[i].fetch_add(1);
    return {};
  }));
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i].load(), 1) << i;

  std::atomic<int> ran{0};
  const Status s = parallelFor(1000, 0, &pool, [&](size_t i) -> Status {
    ran.fetch_add(1);
    if (i == 10) return makeError(ErrorKind::InvalidInput, "tile 10 is bad");
    return {};
  });
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().message, "tile 10 is bad");
  EXPECT_LT(ran.load(), 1000) << "the error stopped the others";
  // Without a runner: a pool made for the call.
  std::atomic<int> count{0};
  EXPECT_TRUE(parallelFor(64, 2, [&](size_t) -> Status {
    count.fetch_add(1);
    return {};
  }));
  EXPECT_EQ(count.load(), 64);
}

TEST(CappedRunner, ALoopOnItPostsAtMostTheCapOfHelpersAndTheRunnerRunsThem) {
  ManualTaskRunner tasks;
  // A pool of 16 offers 16 at once; capped, it offers the cap (or all it has, if fewer).
  ThreadPool pool(16);
  EXPECT_EQ(CappedRunner(pool, 2).concurrency(), 2);
  EXPECT_EQ(CappedRunner(pool, 64).concurrency(), 16) << "never more than the runner has";
  CappedRunner capped(tasks, 1);
  std::vector<int> seen(40, 0);
  EXPECT_TRUE(parallelFor(seen.size(), 0, &capped, [&](size_t i) -> Status {
    ++seen[i];
    return {};
  }));
  EXPECT_EQ(tasks.pending(), 1u) << "cap 1: one helper beside the caller, posted to the runner underneath";
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << i;
  EXPECT_EQ(tasks.runAll(), 1u);
}

}  // namespace
}  // namespace vegstream
