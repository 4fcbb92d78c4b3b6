#pragma once
// GPU figures of one frame as plain numbers: timestamps around each pass and one pipeline-
// statistics query over the frame.

#include <cstdint>
#include <string>
#include <vector>

namespace vegstream::render {

struct PassTime {
  std::string pass;
  double ms = 0.0;
};

struct PipelineStatistics {
  bool available = false;
  uint64_t inputVertices = 0;
  uint64_t inputPrimitives = 0;
  uint64_t vertexInvocations = 0;
  uint64_t clippingInvocations = 0;
  uint64_t clippingPrimitives = 0;
  uint64_t fragmentInvocations = 0;
  uint64_t tessControlPatches = 0;
  uint64_t tessEvaluationInvocations = 0;
  uint64_t geometryInvocations = 0;
  uint64_t geometryPrimitives = 0;
  uint64_t computeInvocations = 0;
};

struct GpuTimings {
  double frameMs = 0.0;  // first to last timestamp of the frame
  std::vector<PassTime> passes;
  // False on a CPU rasteriser such as lavapipe, which runs geometry work when the command
  // buffer is flushed: its per-pass times are not what the passes cost, so callers print
  // only frameMs.
  bool perPassMeaningful = true;
  PipelineStatistics statistics;
};

}  // namespace vegstream::render
