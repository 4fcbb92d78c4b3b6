// A batch of fetches under one deadline (ground_fetch.h).

#include "streaming/ground_fetch.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <utility>

namespace vegstream::streaming {
namespace {

std::atomic<RequestId> nextBatchId{RequestId(1) << 62};  // the streamer counts from 1

// Results arrive on the source's threads and are taken on the caller's.
struct Inbox {
  std::mutex mutex;
  std::condition_variable arrived;
  std::deque<std::pair<size_t, FetchResult>> results;
};

}  // namespace

void fetchBatch(TileSource& source, const std::vector<std::string>& paths, const BatchFetchOptions& options,
                const std::function<void(size_t, FetchResult&&)>& take) {
  auto inbox = std::make_shared<Inbox>();
  std::vector<RequestId> ids(paths.size());
  std::vector<bool> answered(paths.size(), false);
  for (size_t i = 0; i < paths.size(); ++i) {
    ids[i] = nextBatchId++;
    source.start(ids[i], paths[i], [inbox, i](FetchResult&& r) {
      std::lock_guard lock(inbox->mutex);
      inbox->results.emplace_back(i, std::move(r));
      inbox->arrived.notify_one();
    });
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(options.deadlineMs);
  bool late = false;
  for (size_t left = paths.size(); left > 0;) {
    std::unique_lock lock(inbox->mutex);
    if (!inbox->arrived.wait_until(lock, deadline, [&] { return !inbox->results.empty(); }) && !late) {
      late = true;  // cancel what is left; its callbacks still come, as Cancelled
      lock.unlock();
      for (size_t i = 0; i < paths.size(); ++i)
        if (!answered[i]) source.cancel(ids[i]);
      continue;
    }
    if (inbox->results.empty()) {
      inbox->arrived.wait(lock, [&] { return !inbox->results.empty(); });
    }
    auto [index, result] = std::move(inbox->results.front());
    inbox->results.pop_front();
    lock.unlock();
    answered[index] = true;
    --left;
    if (late && result.outcome == FetchOutcome::Cancelled) {
      result.outcome = FetchOutcome::Failed;
      result.message = source.describe() + "/" + paths[index] + ": not answered within the deadline of " +
                       std::to_string(options.deadlineMs) + " ms";
    }
    take(index, std::move(result));
  }
}

}  // namespace vegstream::streaming
