// TileStreamer, completions → resident tiles (tile_streamer_impl.h): a decoded tile is admitted
// when room can be made by evicting least-recently-used tiles (never a current want, never a GPU
// tile drawn this frame); failures and missing tiles are recorded; the frame's figures.

#include <algorithm>
#include <cassert>
#include <chrono>

#include "streaming/tile_streamer_impl.h"

namespace vegstream::streaming {

void TileStreamer::Impl::evictCpu(const TileKey& key) {
  auto it = table.find(key);
  assert(it != table.end() && isResident(it->second.state));
  Entry& e = it->second;
  if (isOnGpu(e.state)) {
    slots.release(e.slot, frame);
    ++stats.evictionsGpu;
  }
  bytesCpu -= e.tile->bytes;
  --tilesCpu;
  ++stats.evictionsCpu;
  residencyChanges.push_back(key);
  if (wanted.contains(key)) {  // a look-ahead want: keep the entry, it may be requested again
    e.state = TileState::Unloaded;
    e.tile.reset();
  } else {
    table.erase(it);
  }
}

// Evicts least-recently-used tiles until `bytes` more fit. Never a current want, never a GPU
// tile used this frame; look-ahead wants go after tiles nobody wants. False (nothing evicted)
// when even that cannot make room.
bool TileStreamer::Impl::makeRoom(uint64_t bytes) {
  if (bytesCpu + bytes <= options.cpuBudgetBytes) return true;
  struct Candidate {
    bool lookAhead;
    uint64_t lastUsed;
    double since;
    TileKey key;
    uint64_t bytes;
  };
  std::vector<Candidate> candidates;
  uint64_t freeable = 0;
  for (const auto& [key, e] : table) {
    if (!isResident(e.state) || isCurrentWant(key)) continue;
    if (isOnGpu(e.state) && e.lastUsedFrame == frame) continue;
    candidates.push_back({wanted.contains(key), e.lastUsedFrame, e.tile->residentSinceS, key, e.tile->bytes});
    freeable += e.tile->bytes;
  }
  if (bytesCpu - freeable + bytes > options.cpuBudgetBytes) return false;
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.lookAhead != b.lookAhead) return !a.lookAhead;
    if (a.lastUsed != b.lastUsed) return a.lastUsed < b.lastUsed;
    if (a.since != b.since) return a.since < b.since;
    return a.key < b.key;
  });
  for (const auto& c : candidates) {
    if (bytesCpu + bytes <= options.cpuBudgetBytes) break;
    evictCpu(c.key);
  }
  return true;
}

void TileStreamer::Impl::admit(const TileKey& key, Completion& c, double timeS) {
  auto tile = std::make_shared<ResidentTile>();
  tile->key = key;
  tile->heights = std::move(c.heights);
  tile->colors = std::move(c.colors);
  tile->extra = std::move(c.extra);
  const uint64_t pixels = tile->heights ? tile->heights->heights.size() * sizeof(float) : tile->colors->rgba.size();
  tile->bytes = pixels + kTileOverheadBytes + (tile->extra ? tile->extra->bytes() : 0);
  tile->residentSinceS = timeS;
  Entry& e = table[key];
  if (!makeRoom(tile->bytes)) {
    // Only the current wants are left and this one does not fit beside them: drop it.
    e.state = TileState::Unloaded;
    ++stats.requestsCancelled;
    if (isCurrentWant(key)) {
      e.blockedByBudget = true;
      stats.wantsExceedCpuBudget = true;
    }
    log->debug("tile {} dropped: it does not fit the CPU budget beside the tiles wanted now", toString(key));
    return;
  }
  e.state = TileState::ResidentCpu;
  e.tile = std::move(tile);
  e.failures = 0;
  e.failure.reset();
  e.lastUsedFrame = frame;
  bytesCpu += e.tile->bytes;
  ++tilesCpu;
  ++stats.requestsCompleted;
  residencyChanges.push_back(key);
}

// What settle() held back, then what the pipeline has; `inRequestOrder` sorts them by request
// (stable: a request's Fetched stays before its final completion), so a batch is taken in the
// same order whatever order the workers finished in.
void TileStreamer::Impl::takeCompletions(double timeS, bool inRequestOrder) {
  std::vector<Completion> batch = std::exchange(heldBack, {});
  for (Completion& c : pipeline->takeCompletions()) batch.push_back(std::move(c));
  if (inRequestOrder)
    std::stable_sort(batch.begin(), batch.end(), [](const Completion& a, const Completion& b) { return a.id < b.id; });
  for (Completion& c : batch) {
    const auto a = active.find(c.id);
    if (a == active.end()) continue;  // cancelled after the pipeline queued it: dropped
    const TileKey key = a->second;
    Entry& e = table[key];
    assert(e.request == c.id);
    if (c.kind == Completion::Kind::Fetched) {
      stats.bytesRead += c.bytes;
      e.state = TileState::Decoding;
      continue;
    }
    active.erase(a);
    e.request = 0;
    switch (c.kind) {
      case Completion::Kind::Fetched: break;
      case Completion::Kind::Missing:
        e.state = TileState::Failed;
        ++stats.requestsMissing;
        log->debug("tile {} is missing ({}): its parent is drawn", toString(key), c.message);
        break;
      case Completion::Kind::FetchFailed:
        if (c.permanent) {  // not a tile a retry can fetch (no regular file, past the ceiling)
          e.state = TileState::Failed;
          ++stats.requestsFailed;
          e.failure = TileStreamer::Failure{c.message, false};
          log->warn("tile {} cannot be read: {}; its parent is drawn", toString(key), c.message);
          break;
        }
        e.state = TileState::FailedTemporarily;
        e.failedAtS = timeS;
        ++e.failures;
        ++stats.requestsFailed;
        e.failure = TileStreamer::Failure{c.message, false};
        log->warn("tile {} failed after {} attempt(s): {}; asking again in {} s", toString(key), c.attempts, c.message,
                  options.failedRetryAfterS);
        break;
      case Completion::Kind::Cancelled:
        e.state = TileState::Unloaded;
        ++stats.requestsCancelled;
        break;
      case Completion::Kind::DecodeFailed:
        e.state = TileState::Failed;
        ++stats.requestsFailed;
        e.failure = TileStreamer::Failure{c.message, true};
        log->warn("tile {} cannot be decoded: {}", toString(key), c.message);
        break;
      case Completion::Kind::Decoded: admit(key, c, timeS); break;
    }
  }
}

void TileStreamer::Impl::refreshTotals() {
  stats.tilesResidentCpu = tilesCpu;
  stats.bytesResidentCpu = bytesCpu;
  stats.tilesResidentGpu = slots.inUse();
  stats.bytesResidentGpu = uint64_t(slots.inUse()) * kGpuSlotBytes;
}

void TileStreamer::Impl::finishStats(double timeS) {
  stats.requestsInFlight = 0;
  stats.decodesQueued = 0;
  for (const auto& [id, key] : active)
    (table[key].state == TileState::Requested ? stats.requestsInFlight : stats.decodesQueued) += 1;
  for (const auto& w : ordered) {
    if (w.lookAhead) break;
    const Entry& e = table[w.key];
    ++stats.wanted;
    if (isResident(e.state)) ++stats.wantedResident;
    if (e.state != TileState::Failed) stats.wantedBytes += e.tile ? e.tile->bytes : tileBytesEstimate(w.key);
    if (!isResident(e.state) && e.state != TileState::Failed)
      stats.longestWaitS = std::max(stats.longestWaitS, timeS - e.firstWantedS);
  }
  if (stats.wantedBytes > options.cpuBudgetBytes) stats.wantsExceedCpuBudget = true;
  refreshTotals();
  assert(bytesCpu <= options.cpuBudgetBytes);
}

}  // namespace vegstream::streaming
