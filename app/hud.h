#pragma once
// What the interactive window shows over the terrain: frame rate and a frame-time graph, GPU
// times (per pass only where the device's per-pass times mean something), counts, streaming
// state, the camera's position, recording state, the shared simulation (the wind, with sliders
// that change it, its CPU time, the camera's collider), the sun with a time-of-day slider, and
// the F1 help. Counts that do not exist
// yet are shown as "—", never invented.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/gpu_timing.h"
#include "simulation/simulation_options.h"

namespace vegstream::app {

struct HudState {
  std::string datasetName;
  std::string deviceName;
  double fps = 0.0;
  std::vector<float> frameTimesMs;        // oldest first (the graph)
  std::optional<render::GpuTimings> gpu;  // of the last completed frame
  uint64_t terrainTriangles = 0;
  std::optional<uint64_t> seedTriangles, plants, plantTriangles;  // empty: not produced yet
  std::string streaming;                                          // e.g. "whole dataset resident at zoom 12"
  uint64_t cpuBytes = 0, gpuBytes = 0;
  double latDeg = 0.0, lonDeg = 0.0, altMslM = 0.0, aglM = 0.0;
  double headingDeg = 0.0, pitchDeg = 0.0, speedMps = 0.0;
  bool followTerrain = false;
  bool recording = false;
  double recordingS = 0.0;
  std::size_t recordedKeyframes = 0;
  std::string message;  // last action's result (screenshot saved to …)
  bool showHelp = false;
  // The shared simulation (issue 19).
  bool simulationOn = true;  // SimulationOptions::enabled
  simulation::WindOptions wind;
  std::optional<double> cpuFrameMs;                    // the CPU stages of the last collected frame
  std::optional<double> cpuSimulationMs;               // its simulation step (empty while nothing simulates)
  std::string cameraCollider = "off";                  // camera_collider.h: off, walking, driving
  std::size_t pathColliders = 0, pathWindSources = 0;  // the flight path's own, moving on session time
  // The sun (issue 39): time_of_day.h's describeSun line and the local time of day, hours.
  std::string sun;
  double timeOfDayH = 0.0;
};

// What the user changed on the HUD this frame (its sliders); empty: nothing.
struct HudEdits {
  std::optional<simulation::WindOptions> wind;  // clamped (wind_controls.h clampWind)
  std::optional<double> timeOfDayH;             // the time-of-day slider moved: local hours, 0 … 24
};

// Lays out the HUD in the current ImGui frame (between ImGuiOverlay::begin and end).
HudEdits drawHud(const HudState& state);

// "1.23 MB"-style byte counts and "—" for absent counts (exposed for tests).
std::string formatBytes(uint64_t bytes);
// `absent` is what an empty count shows ("—" where the font has it).
std::string formatCount(const std::optional<uint64_t>& count, const char* absent = "\xE2\x80\x94");

}  // namespace vegstream::app
