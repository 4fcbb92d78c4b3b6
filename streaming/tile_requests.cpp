// TileStreamer, wants → requests (tile_streamer_impl.h): this frame's wants in a fixed order
// (current first, then priority, then key), requests cancelled when no longer wanted, and new
// ones issued only when the tile fits the CPU budget beside the wants it must never evict.

#include <algorithm>
#include <cassert>
#include <chrono>

#include "streaming/paired_fetch.h"
#include "streaming/tile_streamer_impl.h"

namespace vegstream::streaming {

void TileStreamer::Impl::takeWants(std::span<const TileWant> wants, double timeS) {
  std::unordered_map<TileKey, Want, TileKeyHash> next;
  next.reserve(wants.size());
  for (const auto& w : wants) {
    assert(w.key.layer == TileLayer::Height || meta.imagery.has_value());
    auto [it, fresh] = next.try_emplace(w.key, Want{w.priority, w.lookAhead});
    if (!fresh) {  // the same key twice: the stronger claim wins
      it->second.priority = std::max(it->second.priority, w.priority);
      it->second.lookAhead = it->second.lookAhead && w.lookAhead;
    }
  }
  for (const auto& [key, was] : wanted) {
    auto now = next.find(key);
    auto e = table.find(key);
    if (e == table.end()) continue;
    if (now == next.end() || now->second.lookAhead) {
      e->second.firstWantedS = -1.0;
      e->second.blockedByBudget = false;
    }
    if (now == next.end() &&
        (e->second.state == TileState::Unloaded || e->second.state == TileState::FailedTemporarily))
      table.erase(e);
  }
  wanted = std::move(next);
  ordered.clear();
  for (const auto& [key, w] : wanted) {
    ordered.push_back({key, w.priority, w.lookAhead});
    if (!w.lookAhead) {
      Entry& e = table[key];
      if (e.firstWantedS < 0.0) e.firstWantedS = timeS;
      e.blockedByBudget = false;
      if (isResident(e.state)) e.lastUsedFrame = frame;  // wanted = in use
    }
  }
  std::sort(ordered.begin(), ordered.end(), [](const TileWant& a, const TileWant& b) {
    if (a.lookAhead != b.lookAhead) return !a.lookAhead;
    if (a.priority != b.priority) return a.priority > b.priority;
    return a.key < b.key;  // deterministic order among equals
  });
}

void TileStreamer::Impl::cancelRequest(RequestId id) {
  auto it = active.find(id);
  assert(it != active.end());
  const TileKey key = it->second;
  active.erase(it);
  Entry& e = table[key];
  const bool atSource = e.state == TileState::Requested;
  e.state = TileState::Unloaded;
  e.request = 0;
  pipeline->cancel(id);              // first: nothing about it reaches the table any more
  if (atSource) {  // then free the source's worker(s)
    source->cancel(id);
    if (key.layer == TileLayer::Imagery) detail::cancelCompanions(*source, meta, id);
  }
  ++stats.requestsCancelled;
  if (!wanted.contains(key)) table.erase(key);
}

void TileStreamer::Impl::cancelUnwanted() {
  std::vector<RequestId> drop;
  for (const auto& [id, key] : active)
    if (!wanted.contains(key)) drop.push_back(id);
  for (RequestId id : drop) cancelRequest(id);
}

void TileStreamer::Impl::issue(const TileKey& key, Entry& e) {
  if (e.state == TileState::FailedTemporarily) ++stats.retries;
  const RequestId id = ++nextRequest;
  e.state = TileState::Requested;
  e.request = id;
  active.emplace(id, key);
  ++stats.requestsIssued;
  std::string path = datasetRelativePath(key, meta);
  if (key.layer == TileLayer::Imagery) {
    std::vector<detail::CompanionFile> companions = detail::companionsOf(meta, key.id);
    if (!companions.empty()) {
      detail::startPairedFetch(*source, id, key, path, std::move(companions), pipeline);
      return;
    }
  }
  source->start(id, path, [pipe = pipeline, key, path](FetchResult&& r) { pipe->onFetched(key, path, std::move(r)); });
}

// The look-ahead request of lowest priority, to make room for a current want.
std::optional<RequestId> TileStreamer::Impl::weakestLookAheadRequest() const {
  std::optional<RequestId> best;
  double bestPriority = 0.0;
  for (const auto& [id, key] : active) {
    const auto w = wanted.find(key);
    if (w == wanted.end() || !w->second.lookAhead) continue;
    if (!best || w->second.priority < bestPriority) {
      best = id;
      bestPriority = w->second.priority;
    }
  }
  return best;
}

void TileStreamer::Impl::schedule(double timeS, bool settling) {
  // Bytes the wants will hold once what is in flight lands: current wants may never be evicted,
  // so a want is requested only if it fits beside them (no request that is sure to be dropped).
  uint64_t currentBytes = 0, allBytes = 0;
  for (const auto& w : ordered) {
    const auto e = table.find(w.key);
    if (e == table.end()) continue;
    const bool holds = isResident(e->second.state) || e->second.state == TileState::Requested ||
                       e->second.state == TileState::Decoding;
    if (!holds) continue;
    const uint64_t b = e->second.tile ? e->second.tile->bytes : tileBytesEstimate(w.key);
    allBytes += b;
    if (!w.lookAhead) currentBytes += b;
  }
  for (const auto& w : ordered) {
    Entry& e = table[w.key];
    // Settling, time stands still: a current want that failed is asked again at once (up to
    // kSettleFailures in a row); look-ahead ones wait for the flight time to pass.
    const bool due = e.state == TileState::Unloaded || (e.state == TileState::FailedTemporarily &&
                                                        (timeS - e.failedAtS >= options.failedRetryAfterS ||
                                                         (settling && !w.lookAhead && e.failures < kSettleFailures)));
    if (!due) continue;
    const uint64_t held = w.lookAhead ? allBytes : currentBytes;
    const uint64_t estimate = tileBytesEstimate(w.key);
    if (held + estimate > options.cpuBudgetBytes) {
      if (!w.lookAhead) {
        e.blockedByBudget = true;
        stats.wantsExceedCpuBudget = true;
      }
      continue;
    }
    if (active.size() >= size_t(options.maxRequestsInFlight)) {
      if (w.lookAhead) break;  // wants are ordered: only look-ahead ones remain
      const auto victim = weakestLookAheadRequest();
      if (!victim) break;
      allBytes -= tileBytesEstimate(active.at(*victim));
      cancelRequest(*victim);
    }
    issue(w.key, e);
    allBytes += estimate;
    if (!w.lookAhead) currentBytes += estimate;
  }
}

}  // namespace vegstream::streaming
