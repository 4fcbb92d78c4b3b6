#pragma once
// parallelFor: runs work(i) for i in [0, n) on `threads` std::threads (0 = all cores), each
// taking the next index from a shared counter. The first error stops the others from taking
// new indices and is returned. Tiles of one zoom are independent, so this is all the import
// needs from a thread pool.

#include <cstddef>
#include <functional>

#include "core/result.h"

namespace vegstream::datasets {

int resolveThreads(int threads);  // 0 → std::thread::hardware_concurrency() (at least 1)

Status parallelFor(size_t n, int threads, const std::function<Status(size_t index)>& work);

}  // namespace vegstream::datasets
