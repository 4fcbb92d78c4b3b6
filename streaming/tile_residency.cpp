// TileResidency (tile_residency.h): a decoded tile is admitted when room can be made by evicting
// least-recently-used tiles (never a current want, never a GPU tile drawn this frame).

#include "streaming/tile_residency.h"

#include <algorithm>
#include <cassert>
#include <memory>

#include "streaming/upload_planner.h"

namespace vegstream::streaming::detail {

TileResidency::TileResidency(TileTable& table, UploadPlanner& gpu, const StreamingOptions& options,
                             StreamingFrameStats& stats, const Logger& log)
    : table_(table), gpu_(gpu), options_(options), stats_(stats), log_(log) {}

void TileResidency::countTotals(StreamingFrameStats& stats) const {
  stats.tilesResidentCpu = tilesCpu_;
  stats.bytesResidentCpu = bytesCpu_;
}

void TileResidency::evict(const TileKey& key) {
  Entry* found = table_.find(key);
  assert(found && isResident(found->state));
  Entry& e = *found;
  if (isOnGpu(e.state)) gpu_.release(e);
  bytesCpu_ -= e.tile->bytes;
  --tilesCpu_;
  ++stats_.evictionsCpu;
  changes_.push_back(key);
  if (table_.isWanted(key)) {  // a look-ahead want: keep the entry, it may be requested again
    e.state = TileState::Unloaded;
    e.tile.reset();
  } else {
    table_.erase(key);
  }
}

bool TileResidency::makeRoom(uint64_t bytes) {
  if (bytesCpu_ + bytes <= options_.cpuBudgetBytes) return true;
  struct Candidate {
    bool lookAhead;
    uint64_t lastUsed;
    double since;
    TileKey key;
    uint64_t bytes;
  };
  std::vector<Candidate> candidates;
  uint64_t freeable = 0;
  for (const auto& [key, e] : table_.entries()) {
    if (!isResident(e.state) || table_.isCurrentWant(key)) continue;
    if (isOnGpu(e.state) && e.lastUsedFrame == table_.frame()) continue;
    candidates.push_back({table_.isWanted(key), e.lastUsedFrame, e.tile->residentSinceS, key, e.tile->bytes});
    freeable += e.tile->bytes;
  }
  if (bytesCpu_ - freeable + bytes > options_.cpuBudgetBytes) return false;
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.lookAhead != b.lookAhead) return !a.lookAhead;
    if (a.lastUsed != b.lastUsed) return a.lastUsed < b.lastUsed;
    if (a.since != b.since) return a.since < b.since;
    return a.key < b.key;
  });
  for (const auto& c : candidates) {
    if (bytesCpu_ + bytes <= options_.cpuBudgetBytes) break;
    evict(c.key);
  }
  return true;
}

void TileResidency::admit(const TileKey& key, Completion& c, double timeS) {
  auto tile = std::make_shared<ResidentTile>();
  tile->key = key;
  tile->heights = std::move(c.heights);
  tile->colors = std::move(c.colors);
  tile->extra = std::move(c.extra);
  const uint64_t pixels = tile->heights ? tile->heights->heights.size() * sizeof(float) : tile->colors->rgba.size();
  tile->bytes = pixels + kTileOverheadBytes + (tile->extra ? tile->extra->bytes() : 0);
  tile->residentSinceS = timeS;
  Entry& e = table_.entry(key);
  if (!makeRoom(tile->bytes)) {
    // Only the current wants are left and this one does not fit beside them: drop it.
    e.state = TileState::Unloaded;
    ++stats_.requestsCancelled;
    if (table_.isCurrentWant(key)) {
      e.blockedByBudget = true;
      stats_.wantsExceedCpuBudget = true;
    }
    log_->debug("tile {} dropped: it does not fit the CPU budget beside the tiles wanted now", toString(key));
    return;
  }
  e.state = TileState::ResidentCpu;
  e.tile = std::move(tile);
  e.failures = 0;
  e.failure.reset();
  e.lastUsedFrame = table_.frame();
  bytesCpu_ += e.tile->bytes;
  ++tilesCpu_;
  ++stats_.requestsCompleted;
  changes_.push_back(key);
}

}  // namespace vegstream::streaming::detail
