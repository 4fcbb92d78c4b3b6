#pragma once
// parallelFor: runs work(i) for i in [0, n) on tasks of a TaskRunner (core/task_runner.h), each
// worker taking the next index from a shared counter; the calling thread is one of the workers,
// so the loop finishes even when the runner is busy or is a test's ManualTaskRunner that never
// runs anything. The first error stops the others from taking new indices and is returned (an
// exception is rethrown on the calling thread). Tiles of one zoom are independent, so this is
// what the importers and the terrain pass's per-frame copies need from a thread pool.

#include <cstddef>
#include <functional>

#include "core/result.h"
#include "core/task_runner.h"

namespace vegstream {

int resolveThreads(int threads);  // 0 → std::thread::hardware_concurrency() (at least 1)

// Workers on `tasks` (at most `threads` of them, the caller included; 0: the runner's
// concurrency + 1) when it is given, else on a ThreadPool of `threads` − 1 (0: all cores) made
// for this call. `tasks` must outlive the call only.
Status parallelFor(size_t n, int threads, TaskRunner* tasks, const std::function<Status(size_t index)>& work);
inline Status parallelFor(size_t n, int threads, const std::function<Status(size_t index)>& work) {
  return parallelFor(n, threads, nullptr, work);
}

// Work that cannot fail, on `tasks` and the calling thread, or on the calling thread alone
// without a runner (no pool is made).
void parallelEach(size_t n, TaskRunner* tasks, const std::function<void(size_t index)>& work);

}  // namespace vegstream
