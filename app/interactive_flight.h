#pragma once
// `vegstream fly` with a display: the window loop. A fly camera (fly_camera.h) driven by the
// keyboard and mouse (window_input.h), the HUD (hud.h) drawn by the renderer's HUD pass,
// screenshots (P) and flown-path recording (R), and the shared simulation's inputs: the wind
// (keys and HUD sliders, wind_controls.h), a collider following the camera (C,
// camera_collider.h) and the path's own colliders and wind sources; the sun's time of day (= / -
// keys and a HUD slider, time_of_day.h), with automatic exposure smoothed over time. Controls
// are listed in app/README.md and on F1.
//
// For tests, three environment variables change a run without input devices:
//   VEGSTREAM_FLY_SCREENSHOT_FRAME=N  takes a screenshot of frame N (1-based), as P would
//   VEGSTREAM_FLY_NO_HUD=1            starts with the HUD hidden (H toggles it)
//   VEGSTREAM_FLY_COLLIDER=MODE       starts with the camera's collider walking or driving (C)

#include <filesystem>
#include <optional>

#include "app/camera_collider.h"
#include "core/log.h"
#include "flight/path_sampler.h"
#include "scene/scene.h"

struct GLFWwindow;

namespace vegstream::app {

struct InteractiveOptions {
  int frames = 0;                             // > 0: close after this many frames (tests)
  std::filesystem::path outDir;               // screenshots and recorded paths; empty: the current directory
  std::optional<flight::FlightSample> start;  // first pose; default: south of the centre, looking north
  // The path flown from (`fly --path`, else the template): its colliders and wind sources move
  // along their keyframes on the window's session time (seconds since it opened), as they would
  // at that flight time in a recording, and stay at their last keyframe after. The camera is the
  // user's; only start comes from the path's camera keyframes.
  std::optional<flight::FlightPath> path;
  int screenshotAtFrame = 0;                  // > 0: screenshot of that frame (1-based)
  bool hud = true;
  CameraColliderMode collider = CameraColliderMode::Off;  // at the start (C cycles it)
  // Frames in flight, 1 … render::kFramesInFlight: after submitting frame n the loop collects
  // only what exceeds framesInFlight − 1, so the CPU handles input and prepares frame n + 1 while
  // the GPU draws n (and n − 1). The HUD shows the newest collected frame's figures.
  int framesInFlight = 3;
};

// Fills screenshotAtFrame, hud and collider from the environment variables above.
InteractiveOptions withEnvironment(InteractiveOptions options);

// Runs until Esc, the window closing, or options.frames. `scene` must have been opened with
// `window` as its renderer's window. Returns the process exit code.
int runInteractiveFlight(scene::Scene& scene, GLFWwindow* window, const InteractiveOptions& options, const Logger& log);

}  // namespace vegstream::app
