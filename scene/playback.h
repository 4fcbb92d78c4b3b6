#pragma once
// Fixed-step playback of a flight path through the frame driver, as `record` and headless
// `fly` use it: frame i is at flight time i / fps (whatever the machine's speed), up to and
// including the path's end, so the same inputs give the same poses, counts and — on the same
// driver — images. One FrameRecord per frame becomes one row of frames.csv (README.md
// "Recordings" documents every column); every K-th frame can be saved as PNG.
// Writing the recording's files is recording_files.h's.
//
// Pipelined: with framesInFlight = N, frame i + N − 1 is submitted (its path sampled, its scene
// prepared, its commands recorded) before frame i is collected, so the CPU work of the next
// frames runs while the GPU draws. The counts and images do not depend on N (frame_driver.h says
// why); the timings do: wall_ms is the time between consecutive frame completions (frame i
// collected and its row stored, minus frame i − 1 likewise), less the settled-streaming waits and
// the PNG writing that fell between them; the first row also holds filling the pipeline. With
// N = 1 that is the serial frame, path sampling to finished. The CPU stage columns stay per frame.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/result.h"
#include "flight/flight_path.h"
#include "flight/record_table.h"
#include "render/frame_slots.h"
#include "scene/frame_aovs.h"
#include "scene/frame_driver.h"

namespace vegstream::scene {

struct PlaybackOptions {
  double fps = 60.0;                // frames per second of flight time (> 0)
  double warmupS = 0.0;             // frames rendered at t = 0 before recording, not recorded
  std::size_t framesInFlight = render::kFramesInFlight;  // 1 (serial) … kFramesInFlight
  int framesEvery = 0;  // > 0: save frames 0, K, 2K, … as PNG, each with its sidecar JSON (frame_sidecar.h)
  std::filesystem::path framesDir;  // where frame_NNNNN.png go (framesEvery > 0)
  // Beside each saved frame, its measurement AOVs (scene/frame_aovs.h): one more frame, an AOV
  // frame, at the same input right after it, which repeats it (FrameInput::aov: the same terrain,
  // no streaming; the recording's counts are those of a recording without AOVs) — not recorded,
  // its time left out of the next recorded frame's wall time (the GPU's frames in flight still
  // overlap it: leave the AOVs out of recordings whose timings matter).
  AovSelection aovs;
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
  std::size_t framesInFlight = 1;  // PlaybackOptions::framesInFlight
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
