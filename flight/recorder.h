#pragma once
// The recorder: flies a path through a Scene at a fixed time step (deterministic: frame i is at
// flight time i / fps, whatever the machine's speed) and keeps one row of figures per frame —
// the rows of frames.csv (README.md "Recordings" documents every column). Optionally saves
// every K-th frame as PNG. Writing the recording's files is the caller's (record_command).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/result.h"
#include "flight/flight_path.h"
#include "flight/record_table.h"
#include "flight/scene.h"

namespace vegstream::flight {

struct RecorderOptions {
  double fps = 60.0;                  // frames per second of flight time (> 0)
  double warmupS = 0.0;               // frames rendered at t = 0 before recording, not recorded
  int framesEvery = 0;                // > 0: save frames 0, K, 2K, … as PNG
  std::filesystem::path framesDir;    // where frame_NNNNN.png go (framesEvery > 0)
  // Called after each recorded frame (done = frames so far); may be empty.
  std::function<void(std::size_t done, std::size_t total)> progress;
};

struct Recording {
  RecordTable table;                  // frames.csv
  std::vector<std::string> gpuPasses; // the renderer's passes, in order (gpu_<pass>_ms columns)
  bool perPassMeaningful = false;     // GpuTimings::perPassMeaningful of the device
  bool pipelineStatistics = false;    // the device reported pipeline statistics
  std::size_t warmupFrames = 0;
  std::size_t pngFrames = 0;
  double wallS = 0.0;                 // the whole recording, warm-up included
  uint64_t peakRssBytes = 0;          // the process's VmHWM after the recording; 0 if unknown
};

// Frames recorded for a path: t = 0, 1/fps, … up to and including the path's end.
std::size_t frameCount(double durationS, double fps);

// The columns of frames.csv for a renderer with these passes, in file order.
std::vector<RecordColumn> frameColumns(const std::vector<std::string>& gpuPasses);

// "gpu_terrain_ms" for pass "terrain" (lower case; anything but a-z0-9 becomes '_').
std::string gpuPassColumn(const std::string& pass);

// Peak resident set size of this process (VmHWM of /proc/self/status), 0 where unknown.
uint64_t peakResidentBytes();

// Flies `path` (valid and inside the scene: the caller checks) and returns its figures.
// GPU and PNG-writing failures come back as errors.
Result<Recording> recordFlight(Scene& scene, const FlightPath& path, const RecorderOptions& options);

}  // namespace vegstream::flight
