// TileStreamer, settled frames (tile_streamer_impl.h): every request in flight, look-ahead
// included, finishes before its result is taken, and results are taken in request order, so the
// tiles resident after a frame depend on the wants and the flight time only (repeatable
// recordings); the clock only bounds the wait.

#include <algorithm>
#include <cassert>
#include <chrono>

#include "streaming/tile_streamer_impl.h"

namespace vegstream::streaming {

// settle(): waits until every request in flight has its final completion (held back, not yet
// processed); false when `deadlineS` (clock) passed first.
bool TileStreamer::Impl::awaitInFlight(double deadlineS) {
  for (;;) {
    for (Completion& c : pipeline->takeCompletions()) heldBack.push_back(std::move(c));
    const size_t finished = size_t(std::count_if(heldBack.begin(), heldBack.end(), [&](const Completion& c) {
      return c.kind != Completion::Kind::Fetched && active.contains(c.id);
    }));
    if (finished >= active.size()) return true;
    if (clock->nowS() > deadlineS) return false;
    (void)pipeline->waitForCompletions(std::chrono::milliseconds(50));
  }
}

// Current wants not yet resident, failed or too big (for settle()'s time-out warning).
size_t TileStreamer::Impl::currentWantsPending() const {
  size_t n = 0;
  for (const auto& w : ordered) {
    if (w.lookAhead) break;
    const auto it = table.find(w.key);
    const bool done = it != table.end() && (isResident(it->second.state) || it->second.state == TileState::Failed ||
                                            it->second.state == TileState::FailedTemporarily ||
                                            (it->second.state == TileState::Unloaded && it->second.blockedByBudget));
    n += done ? 0 : 1;
  }
  return n;
}

namespace {
// The per-frame counters of StreamingFrameStats (the rest are snapshots of the moment).
constexpr uint64_t StreamingFrameStats::*kFrameCounters[] = {
    &StreamingFrameStats::requestsIssued,    &StreamingFrameStats::requestsCompleted,
    &StreamingFrameStats::requestsCancelled, &StreamingFrameStats::requestsFailed,
    &StreamingFrameStats::requestsMissing,   &StreamingFrameStats::retries,
    &StreamingFrameStats::bytesRead,         &StreamingFrameStats::uploadBytes,
    &StreamingFrameStats::evictionsCpu,      &StreamingFrameStats::evictionsGpu};
}  // namespace

void addFrameCounters(StreamingFrameStats& into, const StreamingFrameStats& from) {
  for (auto counter : kFrameCounters) into.*counter += from.*counter;
}

void setFrameCounters(StreamingFrameStats& into, const StreamingFrameStats& from) {
  for (auto counter : kFrameCounters) into.*counter = from.*counter;
}

double TileStreamer::settle(std::span<const TileWant> wants, double timeS) {
  Impl& m = *impl_;
  const double start = m.clock->nowS();
  ++m.frame;
  m.stats = {};
  m.takeWants(wants, timeS);
  m.cancelUnwanted();
  // Rounds: everything in flight finishes, its results are taken in request order, the next
  // requests are issued; done when nothing more is in flight. No round reads the clock's time
  // into a tile: timeS alone is the streamer's time.
  for (;;) {
    if (!m.awaitInFlight(start + kSettleTimeoutS)) {
      m.log->warn(
          "settle: {} requests still in flight after {:.0f} s ({} wanted tiles not resident); going on "
          "without them (this frame and later ones are no longer repeatable)",
          m.active.size(), kSettleTimeoutS, m.currentWantsPending());
      m.takeCompletions(timeS, true);
      break;
    }
    m.takeCompletions(timeS, true);
    m.schedule(timeS, true);
    if (m.active.empty()) break;
  }
  m.finishStats(timeS);
  return m.clock->nowS() - start;
}

}  // namespace vegstream::streaming
