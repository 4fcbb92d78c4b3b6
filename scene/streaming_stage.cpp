// The streaming stage (streaming_stage.h): its run and its figures — its CPU time and wait, the
// CPU memory, and the tile streamer's frame (streaming::StreamingFrameStats).

#include "scene/streaming_stage.h"

#include <algorithm>
#include <optional>

#include "core/stopwatch.h"
#include "flight/frame_columns.h"
#include "scene/frame_driver.h"

namespace vegstream::scene {

StreamingStage::StreamingStage(streaming::TileStreamer& streamer, terrain::StreamedTerrain& terrain, bool settled,
                               uint64_t groundBytes)
    : streamer_(streamer), terrain_(terrain), settled_(settled), groundBytes_(groundBytes) {}

// Settled streaming: the wants settled round after round until they stop changing (`wants` the
// last round's); returns every round's counters.
streaming::StreamingFrameStats StreamingStage::settle(std::vector<streaming::TileWant>& wants, double timeS) {
  // A wanted tile that turns out missing is replaced by its parent: settle until the wants stop
  // changing (each round can only move wants up the pyramid, so this ends).
  streaming::StreamingFrameStats counted;
  for (int round = 0; round < 32; ++round) {
    streamer_.settle(wants, timeS);
    addFrameCounters(counted, streamer_.frameStats());
    std::vector<streaming::TileWant> again = terrain_.wantsAgain();
    const bool same =
        again.size() == wants.size() && std::equal(again.begin(), again.end(), wants.begin(),
                                                   [](const auto& a, const auto& b) { return a.key == b.key; });
    wants = std::move(again);
    if (same) break;
  }
  return counted;
}

// The uploads this frame records, as the streamer plans them.
void StreamingStage::planUploads() {
  // Settled frames draw everything they waited for; realtime frames keep the per-frame budget.
  planned_ = streamer_.planUploads(settled_ ? std::optional<uint64_t>(UINT64_MAX) : std::nullopt);
  uploads_.clear();
  for (const streaming::Upload& u : planned_)
    if (u.tile && u.tile->colors) {
      const datasets::ColorTile& c = *u.tile->colors;
      uploads_.push_back({u.slot, c.rgba, c.ndvi, c.landcover});
    }
  streamer_.uploadsRecorded(planned_);  // recorded into this frame's commands by submitFrame
}

void StreamingStage::run(FrameContext& context) {
  SceneFrameFigures& fig = context.figures;
  if (context.repeatsLastFrame()) {
    // No selection, no tiles asked for or arriving, nothing to upload (the frame before it
    // recorded its uploads already).
    fig.streaming = streamer_.frameStats();
    context.request.imageryUploads = {};
    return;
  }
  Stopwatch stage;
  // The terrain's selection for the views (its time, with the views', is the terrain's).
  std::vector<streaming::TileWant> wants = terrain_.wants(context.selection, context.eye, context.ahead);
  fig.terrainMs += context.viewsMs + stage.elapsedMs();

  stage.restart();
  double waitMs = 0.0;
  std::optional<streaming::StreamingFrameStats> settledCounters;
  if (settled_) {
    Stopwatch wait;
    settledCounters = settle(wants, context.timeS);
    waitMs = wait.elapsedMs();
  } else {
    streamer_.update(wants, context.timeS);
  }
  planUploads();
  fig.streamingMs = stage.elapsedMs() - waitMs;
  fig.settleWaitMs = waitMs;
  fig.streaming = streamer_.frameStats();
  if (settledCounters) {  // every settle round's requests; the uploads planned after them
    const uint64_t uploadBytes = fig.streaming.uploadBytes;
    setFrameCounters(fig.streaming, *settledCounters);
    fig.streaming.uploadBytes = uploadBytes;
  }
  fig.uploads = uploads_.size();
  fig.cpuBytes = fig.streaming.bytesResidentCpu + groundBytes_;
  context.request.imageryUploads = uploads_;
}

void StreamingStage::declareFigures(FrameFigures& out, const FigureLayout&) {
  using S = FigureSection;
  using R = const FrameRecord&;
  using Stats = streaming::StreamingFrameStats;
  namespace col = flight::column;
  out.push_back({S::CpuStages, {"cpu_streaming_ms", 6, "ms"}, [](R r) { return r.scene.streamingMs; }});
  out.push_back({S::Memory, {col::kCpuBytes, 0, "bytes"}, [](R r) { return count(r.scene.cpuBytes); }});
  // Settled mode's wait, left out of the frame time.
  out.push_back({S::Streaming, {col::kStreamingWaitMs, 4, "ms"}, [](R r) { return r.scene.settleWaitMs; }});
  // The oldest wanted tile not resident yet.
  out.push_back(
      {S::Streaming, {"stream_longest_wait_ms", 1, "ms"}, [](R r) { return r.scene.streaming.longestWaitS * 1000.0; }});
  const auto counter = [&out](const char* name, const char* unit, uint64_t Stats::*field) {
    out.push_back({S::Streaming, {name, 0, unit}, [field](R r) { return count(r.scene.streaming.*field); }});
  };
  counter(col::kRequestsIssued, "requests", &Stats::requestsIssued);
  counter(col::kRequestsCompleted, "requests", &Stats::requestsCompleted);
  counter(col::kRequestsCancelled, "requests", &Stats::requestsCancelled);
  counter(col::kRequestsFailed, "requests", &Stats::requestsFailed);
  counter(col::kRequestsMissing, "requests", &Stats::requestsMissing);
  counter(col::kRetries, "requests", &Stats::retries);
  counter(col::kBytesRead, "bytes", &Stats::bytesRead);
  out.push_back({S::Streaming, {col::kUploads, 0, "tiles"}, [](R r) { return count(r.scene.uploads); }});
  counter("stream_upload_bytes", "bytes", &Stats::uploadBytes);
  counter("stream_evictions_cpu", "tiles", &Stats::evictionsCpu);
  counter("stream_evictions_gpu", "tiles", &Stats::evictionsGpu);
  counter("stream_tiles_resident_cpu", "tiles", &Stats::tilesResidentCpu);
  counter("stream_tiles_resident_gpu", "tiles", &Stats::tilesResidentGpu);
  counter(col::kBytesResidentCpu, "bytes", &Stats::bytesResidentCpu);
  counter(col::kBytesResidentGpu, "bytes", &Stats::bytesResidentGpu);
  counter("stream_requests_in_flight", "requests", &Stats::requestsInFlight);
  counter("stream_wanted", "tiles", &Stats::wanted);
  counter("stream_wanted_resident", "tiles", &Stats::wantedResident);
}

}  // namespace vegstream::scene
