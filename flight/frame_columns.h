#pragma once
// Names of frames.csv's columns that readers of a recording pick out (the summary, the plots'
// totals), and the name of a GPU pass's column. The columns themselves — which exist, in which
// order, with which decimals — are declared by the frame's stages (scene/frame_figures.h) and
// documented in README.md "Recordings"; the declarations use these names, so a reader that picks
// a column by one of them picks the declared column. flight/ knows no stage: a recording read back
// from disk is summarised by these names alone.

#include <string>

namespace vegstream::flight::column {

inline constexpr const char* kFrame = "frame";
inline constexpr const char* kTimeS = "t_s";
inline constexpr const char* kCpuFrameMs = "cpu_frame_ms";
inline constexpr const char* kGpuFrameMs = "gpu_frame_ms";
inline constexpr const char* kWallMs = "wall_ms";
inline constexpr const char* kRecorderMs = "recorder_ms";
inline constexpr const char* kPngMs = "png_ms";
inline constexpr const char* kTerrainTriangles = "terrain_triangles";
inline constexpr const char* kCpuBytes = "cpu_bytes";
inline constexpr const char* kGpuBytes = "gpu_bytes";
inline constexpr const char* kStreamingWaitMs = "streaming_wait_ms";
inline constexpr const char* kRequestsIssued = "stream_requests_issued";
inline constexpr const char* kRequestsCompleted = "stream_requests_completed";
inline constexpr const char* kRequestsCancelled = "stream_requests_cancelled";
inline constexpr const char* kRequestsFailed = "stream_requests_failed";
inline constexpr const char* kRequestsMissing = "stream_requests_missing";
inline constexpr const char* kRetries = "stream_retries";
inline constexpr const char* kBytesRead = "stream_bytes_read";
inline constexpr const char* kUploads = "stream_uploads";
inline constexpr const char* kBytesResidentCpu = "stream_bytes_resident_cpu";
inline constexpr const char* kBytesResidentGpu = "stream_bytes_resident_gpu";
inline constexpr const char* kFallbackPieces = "terrain_fallback_pieces";
inline constexpr const char* kMaxLevelsCoarser = "terrain_max_levels_coarser";
inline constexpr const char* kErrorRelaxation = "terrain_error_relaxation";

// "gpu_terrain_ms" for pass "terrain" (lower case; anything but a-z0-9 becomes '_').
std::string gpuPassColumn(const std::string& pass);

}  // namespace vegstream::flight::column
