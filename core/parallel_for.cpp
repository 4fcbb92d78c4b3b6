// parallelFor (parallel_for.h): a shared atomic index over tasks of a runner plus the calling thread,
// first error wins. The state is shared with the posted tasks, so one that starts after the
// loop returned finds it closed and touches nothing else.

#include "core/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

namespace vegstream {
namespace {

struct Loop {
  size_t n = 0;
  const std::function<Status(size_t)>* work = nullptr;  // valid while !closed
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::condition_variable idle;
  int running = 0;      // workers inside the loop
  bool closed = false;  // the caller has returned (or is about to): late tasks do nothing
  std::optional<Error> firstError;
  std::exception_ptr firstException;

  void runWorker() {
    {
      std::lock_guard lock(mutex);
      if (closed) return;
      ++running;
    }
    while (!failed.load(std::memory_order_relaxed)) {
      const size_t i = next.fetch_add(1);
      if (i >= n) break;
      try {
        Status s = (*work)(i);
        if (!s) {
          std::lock_guard lock(mutex);
          if (!firstError && !firstException) firstError = s.error();
          failed = true;
        }
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!firstError && !firstException) firstException = std::current_exception();
        failed = true;
      }
    }
    std::lock_guard lock(mutex);
    if (--running == 0) idle.notify_all();
  }
};

}  // namespace

int resolveThreads(int threads) {
  if (threads > 0) return threads;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

Status parallelFor(size_t n, int threads, TaskRunner* tasks, const std::function<Status(size_t)>& work) {
  if (n == 0) return {};
  std::unique_ptr<ThreadPool> ownPool;
  const int workers = threads > 0 ? threads : (tasks ? tasks->concurrency() + 1 : resolveThreads(0));
  const size_t helpers = std::min(n, static_cast<size_t>(workers)) - 1;
  if (!tasks && helpers > 0) {
    ownPool = std::make_unique<ThreadPool>(static_cast<int>(helpers));
    tasks = ownPool.get();
  }
  auto loop = std::make_shared<Loop>();
  loop->n = n;
  loop->work = &work;
  for (size_t i = 0; i < helpers; ++i) tasks->post([loop] { loop->runWorker(); });
  loop->runWorker();
  {
    std::unique_lock lock(loop->mutex);
    loop->closed = true;
    loop->idle.wait(lock, [&] { return loop->running == 0; });
  }
  if (loop->firstException) std::rethrow_exception(loop->firstException);
  if (loop->firstError) return *loop->firstError;
  return {};
}

void parallelEach(size_t n, TaskRunner* tasks, const std::function<void(size_t)>& work) {
  const Status s = parallelFor(n, tasks ? 0 : 1, tasks, [&](size_t k) -> Status {
    work(k);
    return {};
  });
  assert(s.ok());
  (void)s;
}

}  // namespace vegstream
