// The streaming stage's figures (frame_figures.h): its CPU time and wait, the CPU memory, and the
// tile streamer's frame (streaming::StreamingFrameStats).

#include "flight/frame_columns.h"
#include "scene/frame_driver.h"
#include "scene/frame_figures.h"

namespace vegstream::scene {

void declareStreamingFigures(FrameFigures& out, const FigureLayout&) {
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
