// RequestScheduler (request_scheduler.h): requests cancelled when no longer wanted, and new ones
// issued in the wants' order only when the tile fits the CPU budget beside the wants it must
// never evict.

#include "streaming/request_scheduler.h"

#include <cassert>
#include <string>
#include <utility>
#include <vector>

#include "streaming/paired_fetch.h"

namespace vegstream::streaming::detail {

RequestScheduler::RequestScheduler(TileTable& table, TileSource& source, std::shared_ptr<DecodePipeline> pipeline,
                                   const datasets::DatasetMeta& meta, const StreamingOptions& options,
                                   StreamingFrameStats& stats)
    : table_(table), source_(source), pipeline_(std::move(pipeline)), meta_(meta), options_(options), stats_(stats) {}

const TileKey* RequestScheduler::keyOf(RequestId id) const {
  const auto it = active_.find(id);
  return it == active_.end() ? nullptr : &it->second;
}

void RequestScheduler::countInFlight(StreamingFrameStats& stats) const {
  stats.requestsInFlight = 0;
  stats.decodesQueued = 0;
  for (const auto& [id, key] : active_)
    (table_.state(key) == TileState::Requested ? stats.requestsInFlight : stats.decodesQueued) += 1;
}

void RequestScheduler::cancelAtSource() {
  for (const auto& [id, key] : active_)
    if (table_.state(key) == TileState::Requested) {
      source_.cancel(id);
      if (key.layer == TileLayer::Imagery) cancelCompanions(source_, meta_, id);
    }
}

void RequestScheduler::cancel(RequestId id) {
  auto it = active_.find(id);
  assert(it != active_.end());
  const TileKey key = it->second;
  active_.erase(it);
  Entry& e = table_.entry(key);
  const bool atSource = e.state == TileState::Requested;
  e.state = TileState::Unloaded;
  e.request = 0;
  pipeline_->cancel(id);  // first: nothing about it reaches the table any more
  if (atSource) {         // then free the source's worker(s)
    source_.cancel(id);
    if (key.layer == TileLayer::Imagery) cancelCompanions(source_, meta_, id);
  }
  ++stats_.requestsCancelled;
  if (!table_.isWanted(key)) table_.erase(key);
}

void RequestScheduler::cancelUnwanted() {
  std::vector<RequestId> drop;
  for (const auto& [id, key] : active_)
    if (!table_.isWanted(key)) drop.push_back(id);
  for (RequestId id : drop) cancel(id);
}

void RequestScheduler::issue(const TileKey& key, Entry& e) {
  if (e.state == TileState::FailedTemporarily) ++stats_.retries;
  const RequestId id = ++nextRequest_;
  e.state = TileState::Requested;
  e.request = id;
  active_.emplace(id, key);
  ++stats_.requestsIssued;
  std::string path = datasetRelativePath(key, meta_);
  if (key.layer == TileLayer::Imagery) {
    std::vector<CompanionFile> companions = companionsOf(meta_, key.id);
    if (!companions.empty()) {
      startPairedFetch(source_, id, key, path, std::move(companions), pipeline_);
      return;
    }
  }
  source_.start(id, path, [pipe = pipeline_, key, path](FetchResult&& r) { pipe->onFetched(key, path, std::move(r)); });
}

std::optional<RequestId> RequestScheduler::weakestLookAheadRequest() const {
  std::optional<RequestId> best;
  double bestPriority = 0.0;
  for (const auto& [id, key] : active_) {
    const Want* w = table_.want(key);
    if (!w || !w->lookAhead) continue;
    if (!best || w->priority < bestPriority) {
      best = id;
      bestPriority = w->priority;
    }
  }
  return best;
}

std::pair<uint64_t, uint64_t> RequestScheduler::heldBytes() const {
  // Current wants may never be evicted, so a want is requested only if it fits beside them (no
  // request that is sure to be dropped).
  uint64_t currentBytes = 0, allBytes = 0;
  for (const auto& w : table_.ordered()) {
    const Entry* e = table_.find(w.key);
    if (!e) continue;
    const bool holds = isResident(e->state) || e->state == TileState::Requested || e->state == TileState::Decoding;
    if (!holds) continue;
    const uint64_t b = e->tile ? e->tile->bytes : table_.bytesEstimate(w.key);
    allBytes += b;
    if (!w.lookAhead) currentBytes += b;
  }
  return {currentBytes, allBytes};
}

void RequestScheduler::schedule(double timeS, bool settling) {
  auto [currentBytes, allBytes] = heldBytes();
  for (const auto& w : table_.ordered()) {
    Entry& e = table_.entry(w.key);
    // Settling, time stands still: a current want that failed is asked again at once (up to
    // kSettleFailures in a row); look-ahead ones wait for the flight time to pass.
    const bool due = e.state == TileState::Unloaded || (e.state == TileState::FailedTemporarily &&
                                                        (timeS - e.failedAtS >= options_.failedRetryAfterS ||
                                                         (settling && !w.lookAhead && e.failures < kSettleFailures)));
    if (!due) continue;
    const uint64_t held = w.lookAhead ? allBytes : currentBytes;
    const uint64_t estimate = table_.bytesEstimate(w.key);
    if (held + estimate > options_.cpuBudgetBytes) {
      if (!w.lookAhead) {
        e.blockedByBudget = true;
        stats_.wantsExceedCpuBudget = true;
      }
      continue;
    }
    if (active_.size() >= size_t(options_.maxRequestsInFlight)) {
      if (w.lookAhead) break;  // wants are ordered: only look-ahead ones remain
      const auto victim = weakestLookAheadRequest();
      if (!victim) break;
      allBytes -= table_.bytesEstimate(active_.at(*victim));
      cancel(*victim);
    }
    issue(w.key, e);
    allBytes += estimate;
    if (!w.lookAhead) currentBytes += estimate;
  }
}

}  // namespace vegstream::streaming::detail
