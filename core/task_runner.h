#pragma once
// TaskRunner: where background work runs. Components that need threads (the streamer's decode
// work, the tile sources' I/O, the importers' parallel loops) are given a runner when they are
// made, never start threads themselves and never reach for a global one — the same shape as
// cesium-native's AsyncSystem over an injected ITaskProcessor.
//
// - ThreadPool: the one owner of worker threads in the program. post() queues a task for its
//   workers; postLongRunning() gives a task that runs until its owner stops it (the HTTP
//   source's libcurl loop) a thread of its own, also owned and joined by the pool. The
//   destructor runs what is still queued, then joins every thread: owners must have told their
//   long-running tasks to return first.
// - ManualTaskRunner: for tests. Nothing runs until the test says so (runOne, runAll), on the
//   test's own thread, in the order posted; long-running tasks are queued like the others and
//   must return when run.
//
// A task must not throw (an escaping exception ends the program, as it would on a std::thread).

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace vegstream {

using Task = std::function<void()>;

class TaskRunner {
 public:
  virtual ~TaskRunner() = default;
  // Any thread. Runs `task` later, never inside post().
  virtual void post(Task task) = 0;
  // Any thread. A task that runs for a long time (a loop its owner stops): it never holds back
  // the tasks given to post().
  virtual void postLongRunning(Task task) = 0;
  // How many posted tasks may run at once (for sizing batches): at least 1.
  virtual int concurrency() const = 0;
};

class ThreadPool final : public TaskRunner {
 public:
  // `threads` workers for post(); 0: std::thread::hardware_concurrency() (at least 1).
  explicit ThreadPool(int threads = 0);
  ~ThreadPool() override;
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  void post(Task task) override;
  void postLongRunning(Task task) override;
  int concurrency() const override { return static_cast<int>(workers_.size()); }

 private:
  void work();

  std::mutex mu_;
  std::condition_variable wake_;
  std::deque<Task> queue_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
  std::vector<std::thread> dedicated_;  // postLongRunning's
};

class ManualTaskRunner final : public TaskRunner {
 public:
  void post(Task task) override;
  void postLongRunning(Task task) override { post(std::move(task)); }
  int concurrency() const override { return 1; }

  // The oldest queued task, on the caller's thread; false when none was queued.
  bool runOne();
  // Runs tasks until none is queued (including those posted meanwhile); returns how many ran.
  std::size_t runAll();
  std::size_t pending() const;

 private:
  mutable std::mutex mu_;
  std::deque<Task> queue_;
};

}  // namespace vegstream
