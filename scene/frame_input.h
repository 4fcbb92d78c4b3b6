#pragma once
// What the caller of the frame driver (frame_driver.h) decides about one frame: the pose and the
// time, the poses expected next, the simulation's inputs, the sun's clock, and what to read back
// or present. Plain data; the frame's context (frame_context.h) points at it while the stages run.

#include <optional>
#include <vector>

#include "flight/path_sampler.h"
#include "render/frame_types.h"

namespace vegstream::scene {

// What the caller decides about a frame: the camera, the time, the poses expected next.
struct FrameInput {
  flight::FlightSample pose;
  double timeS = 0.0;                       // flight time (scripted) or session time (window)
  std::vector<flight::FlightSample> ahead;  // look-ahead poses (ignored without look-ahead)
  // The shared simulation's inputs at this instant (flight/path_sampler.h): the path's colliders
  // and wind sources, and the simulation's own clock when it differs from timeS (a still holds
  // its scene time while the simulation runs on: app/settled_still.h).
  std::vector<flight::ColliderSample> colliders;
  std::vector<flight::WindSourceSample> windSources;
  std::optional<double> simulationTimeS;
  // The sun's clock (Scene::sunClock) when it differs from timeS: a still holds its date-time
  // while the scene settles.
  std::optional<double> sunTimeS;
  bool adaptExposure = false;  // the window: automatic exposure smoothed over time
  double flightMs = 0.0;       // what the caller spent producing pose and ahead
  bool present = false;        // to the window, when the renderer has one
  bool readbackColor = false;
  // An AOV frame (render::FrameRequest::aov): FrameRecord::aov comes back instead of a colour.
  // It repeats the frame submitted before it (the same input): the streaming and the terrain
  // hand on what they handed on then, changing nothing the frames after it see.
  bool aov = false;
  const render::OverlayDrawData* overlay = nullptr;  // must stay alive until submit() returns
};

}  // namespace vegstream::scene
