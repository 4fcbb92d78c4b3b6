// CompletionIntake (completion_intake.h): the outcomes of requests, taken in on the frame thread;
// in request order while settling, so the tiles resident afterwards do not depend on when I/O or
// decoding ended.

#include "streaming/completion_intake.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <utility>

#include "streaming/request_scheduler.h"
#include "streaming/tile_residency.h"

namespace vegstream::streaming::detail {

CompletionIntake::CompletionIntake(DecodePipeline& pipeline, TileTable& table, RequestScheduler& requests,
                                   TileResidency& residency, const StreamingOptions& options,
                                   StreamingFrameStats& stats, const Logger& log)
    : pipeline_(pipeline), table_(table), requests_(requests), residency_(residency), options_(options), stats_(stats),
      log_(log) {}

bool CompletionIntake::awaitInFlight(const Clock& clock, double deadlineS) {
  for (;;) {
    for (Completion& c : pipeline_.takeCompletions()) heldBack_.push_back(std::move(c));
    const size_t finished = size_t(std::count_if(heldBack_.begin(), heldBack_.end(), [&](const Completion& c) {
      return c.kind != Completion::Kind::Fetched && requests_.keyOf(c.id);
    }));
    if (finished >= requests_.inFlight()) return true;
    if (clock.nowS() > deadlineS) return false;
    (void)pipeline_.waitForCompletions(std::chrono::milliseconds(50));
  }
}

void CompletionIntake::take(double timeS, bool inRequestOrder) {
  std::vector<Completion> batch = std::exchange(heldBack_, {});
  for (Completion& c : pipeline_.takeCompletions()) batch.push_back(std::move(c));
  if (inRequestOrder)
    std::stable_sort(batch.begin(), batch.end(), [](const Completion& a, const Completion& b) { return a.id < b.id; });
  for (Completion& c : batch) {
    const TileKey* inFlight = requests_.keyOf(c.id);
    if (!inFlight) continue;  // cancelled after the pipeline queued it: dropped
    const TileKey key = *inFlight;
    Entry& e = table_.entry(key);
    assert(e.request == c.id);
    if (c.kind == Completion::Kind::Fetched) {
      stats_.bytesRead += c.bytes;
      e.state = TileState::Decoding;
      continue;
    }
    requests_.finish(c.id);
    e.request = 0;
    apply(key, e, c, timeS);
  }
}

void CompletionIntake::apply(const TileKey& key, Entry& e, Completion& c, double timeS) {
  switch (c.kind) {
    case Completion::Kind::Fetched: break;
    case Completion::Kind::Missing:
      e.state = TileState::Failed;
      ++stats_.requestsMissing;
      log_->debug("tile {} is missing ({}): its parent is drawn", toString(key), c.message);
      break;
    case Completion::Kind::FetchFailed:
      if (c.permanent) {  // not a tile a retry can fetch (no regular file, past the ceiling)
        e.state = TileState::Failed;
        ++stats_.requestsFailed;
        e.failure = TileStreamer::Failure{c.message, false};
        log_->warn("tile {} cannot be read: {}; its parent is drawn", toString(key), c.message);
        break;
      }
      e.state = TileState::FailedTemporarily;
      e.failedAtS = timeS;
      ++e.failures;
      ++stats_.requestsFailed;
      e.failure = TileStreamer::Failure{c.message, false};
      log_->warn("tile {} failed after {} attempt(s): {}; asking again in {} s", toString(key), c.attempts, c.message,
                 options_.failedRetryAfterS);
      break;
    case Completion::Kind::Cancelled:
      e.state = TileState::Unloaded;
      ++stats_.requestsCancelled;
      break;
    case Completion::Kind::DecodeFailed:
      e.state = TileState::Failed;
      ++stats_.requestsFailed;
      e.failure = TileStreamer::Failure{c.message, true};
      log_->warn("tile {} cannot be decoded: {}", toString(key), c.message);
      break;
    case Completion::Kind::Decoded: residency_.admit(key, c, timeS); break;
  }
}

}  // namespace vegstream::streaming::detail
