// parallelFor (parallel.h): a shared atomic index over std::threads, first error wins.

#include "datasets/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace vegstream::datasets {

int resolveThreads(int threads) {
  if (threads > 0) return threads;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

Status parallelFor(size_t n, int threads, const std::function<Status(size_t)>& work) {
  if (n == 0) return {};
  const size_t count = std::min(n, static_cast<size_t>(resolveThreads(threads)));
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::optional<Error> firstError;
  std::exception_ptr firstException;
  auto worker = [&] {
    while (!failed.load(std::memory_order_relaxed)) {
      const size_t i = next.fetch_add(1);
      if (i >= n) return;
      try {
        Status s = work(i);
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
  };
  if (count == 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(count);
    for (size_t t = 0; t < count; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  if (firstException) std::rethrow_exception(firstException);
  if (firstError) return *firstError;
  return {};
}

}  // namespace vegstream::datasets
