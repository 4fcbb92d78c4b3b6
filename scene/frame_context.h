#pragma once
// What every stage of a frame reads about its pose, made once when the frame starts: the flight
// sample and the frame's time, the camera in the scene's local frame (geo/camera.h), the tile
// selection's view and ROAM's eye view of that camera, and the selection views of the look-ahead
// poses. No stage converts the pose again, and the look-ahead poses are only ever views.
//
// Contract: the views are those of camera_views.h for the given viewport; `ahead` is empty when
// the caller passes no look-ahead poses (look-ahead off). A context is plain data, valid as long
// as the caller keeps it.

#include <span>
#include <vector>

#include "flight/path_sampler.h"
#include "geo/camera.h"
#include "geo/local_frame.h"
#include "terrain/eye_space.h"
#include "terrain/tile_selection.h"

namespace vegstream::scene {

struct FrameContext {
  // The pose at `timeS` seen through a viewport of widthPx × heightPx, with the poses expected
  // next (look-ahead) as selection views.
  FrameContext(const geo::LocalFrame& frame, const flight::FlightSample& pose, double timeS,
               std::span<const flight::FlightSample> ahead, double widthPx, double heightPx);

  flight::FlightSample pose;
  double timeS = 0.0;
  geo::Camera camera;
  terrain::SelectionView selection;
  terrain::EyeView eye;
  std::vector<terrain::SelectionView> ahead;
  double viewsMs = 0.0;  // making the above (the terrain stage counts it: its views)
};

}  // namespace vegstream::scene
