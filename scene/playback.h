#pragma once
// Fixed-step playback of a flight path through the frame driver, as `record` and headless
// `fly` use it: frame i is at flight time i / fps (whatever the machine's speed), up to and
// including the path's end, so the same inputs give the same poses, counts and — on the same
// driver — images. One FrameRecord per frame becomes one row of frames.csv (README.md
// "Recordings" documents every column); every K-th frame can be saved as PNG.
// Writing the recording's files is recording_files.h's.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/result.h"
#include "flight/flight_path.h"
#include "flight/record_table.h"
#include "scene/frame_driver.h"

namespace vegstream::scene {

struct PlaybackOptions {
  double fps = 60.0;                // frames per second of flight time (> 0)
  double warmupS = 0.0;             // frames rendered at t = 0 before recording, not recorded
  int framesEvery = 0;              // > 0: save frames 0, K, 2K, … as PNG
  std::filesystem::path framesDir;  // where frame_NNNNN.png go (framesEvery > 0)
  // Called after each recorded frame (done = frames so far); may be empty.
  std::function<void(std::size_t done, std::size_t total)> progress;
};

struct Recording {
  flight::RecordTable table;           // frames.csv
  std::vector<std::string> gpuPasses;  // the renderer's passes, in order (gpu_<pass>_ms columns)
  bool perPassMeaningful = false;      // GpuTimings::perPassMeaningful of the device
  bool pipelineStatistics = false;     // the device reported pipeline statistics
  std::size_t warmupFrames = 0;
  std::size_t pngFrames = 0;
  double wallS = 0.0;         // the whole recording, warm-up included
  uint64_t peakRssBytes = 0;  // the process's VmHWM after the recording; 0 if unknown
};

// The fps that spreads `frames` frames over a path of durationS, first and last pose included
// (headless `fly --frames N`); frameCount(durationS, result) == frames.
double fpsForFrames(double durationS, std::size_t frames);

// Flies `path` (valid and inside the scene: the caller checks) and returns its figures.
// GPU and PNG-writing failures come back as errors.
Result<Recording> playFlight(FrameDriver& driver, const flight::FlightPath& path, const PlaybackOptions& options);

}  // namespace vegstream::scene
