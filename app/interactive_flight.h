#pragma once
// `vegstream fly` with a display: the window loop. A fly camera (fly_camera.h) driven by the
// keyboard and mouse (window_input.h), the HUD (hud.h) drawn by the renderer's HUD pass,
// screenshots (P) and flown-path recording (R). Controls are listed in app/README.md and on
// F1.
//
// For tests, two environment variables change a run without input devices:
//   VEGSTREAM_FLY_SCREENSHOT_FRAME=N  takes a screenshot of frame N (1-based), as P would
//   VEGSTREAM_FLY_NO_HUD=1            starts with the HUD hidden (H toggles it)

#include <filesystem>
#include <optional>

#include "core/log.h"
#include "flight/path_sampler.h"
#include "scene/scene.h"

struct GLFWwindow;

namespace vegstream::app {

struct InteractiveOptions {
  int frames = 0;                             // > 0: close after this many frames (tests)
  std::filesystem::path outDir;               // screenshots and recorded paths; empty: the current directory
  std::optional<flight::FlightSample> start;  // first pose; default: south of the centre, looking north
  int screenshotAtFrame = 0;                  // > 0: screenshot of that frame (1-based)
  bool hud = true;
  // Frames in flight, 1 … render::kFramesInFlight: after submitting frame n the loop collects
  // only what exceeds framesInFlight − 1, so the CPU handles input and prepares frame n + 1 while
  // the GPU draws n (and n − 1). The HUD shows the newest collected frame's figures.
  int framesInFlight = 3;
};

// Fills screenshotAtFrame and hud from the environment variables above.
InteractiveOptions withEnvironment(InteractiveOptions options);

// Runs until Esc, the window closing, or options.frames. `scene` must have been opened with
// `window` as its renderer's window. Returns the process exit code.
int runInteractiveFlight(scene::Scene& scene, GLFWwindow* window, const InteractiveOptions& options, const Logger& log);

}  // namespace vegstream::app
