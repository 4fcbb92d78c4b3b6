#pragma once
// One frame as its stages (frame_stage.h) see it. Made once when the frame starts: the flight
// sample and the frame's time, the camera in the scene's local frame (geo/camera.h), the tile
// selection's view and ROAM's eye view of that camera, and the selection views of the look-ahead
// poses — no stage converts the pose again, and the look-ahead poses are only ever views. Then
// filled by the stages in the list's order: the renderer's request (and the plants' part of it),
// the CPU stages' figures, the simulation's time, the submitted frame.
//
// Contract: the views are those of camera_views.h for the given viewport; `ahead` is empty when
// the caller passes no look-ahead poses (look-ahead off). `input` is the driver's (null when a
// caller runs only the scene's stages). The request points into the context and into the stages'
// storage: valid until the stages run again. Neither copied nor moved (the request points at
// `vegetation`).

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "core/result.h"
#include "flight/path_sampler.h"
#include "geo/camera.h"
#include "geo/local_frame.h"
#include "render/frame_types.h"
#include "scene/scene_frame_figures.h"
#include "terrain/eye_space.h"
#include "terrain/tile_selection.h"

namespace vegstream::scene {

struct FrameInput;

struct FrameContext {
  // The pose `now` at flight time t seen through a viewport of widthPx × heightPx, with the poses
  // expected next (look-ahead) as selection views.
  FrameContext(const geo::LocalFrame& frame, const flight::FlightSample& now, double t,
               std::span<const flight::FlightSample> aheadPoses, double widthPx, double heightPx);
  FrameContext(const FrameContext&) = delete;
  FrameContext& operator=(const FrameContext&) = delete;

  // The views, made once.
  flight::FlightSample pose;
  double timeS = 0.0;
  geo::Camera camera;
  terrain::SelectionView selection;
  terrain::EyeView eye;
  std::vector<terrain::SelectionView> ahead;
  double viewsMs = 0.0;  // making the above (the terrain stage counts it: its views)
  const FrameInput* input = nullptr;
  // An AOV frame (FrameInput::aov): it repeats the frame before it, so the stages that change
  // the scene's state (streaming, terrain) hand on what they handed on then.
  bool repeatsLastFrame() const;

  // What the stages hand on.
  render::FrameRequest request;
  render::VegetationRequest vegetation;  // the plants' request, when the seeding stage makes one
  SceneFrameFigures figures;             // the CPU stages'
  double simulationMs = std::numeric_limits<double>::quiet_NaN();  // NaN: nothing simulated
  std::optional<Result<uint64_t>> submitted;                       // the render stage's frame index
};

}  // namespace vegstream::scene
