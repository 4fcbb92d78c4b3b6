#pragma once
// A flight sample as the camera (geo/camera.h, which the renderer takes too) and as the terrain's
// views of it (the chunked-LOD selection's frustum and ROAM's eye space): one definition shared
// by the frame's context (frame_context.h), the benchmarks and the tests, so all of them see the
// same camera for the same sample.

#include "flight/path_sampler.h"
#include "geo/camera.h"
#include "geo/local_frame.h"
#include "terrain/eye_space.h"
#include "terrain/tile_selection.h"

namespace vegstream::scene {

using flight::FlightSample;

// Heading and pitch are relative to the local east/north/up at the camera, which tilts away from
// the frame's axes with distance from its origin (earth curvature).
geo::Camera cameraFor(const geo::LocalFrame& frame, const FlightSample& sample);
terrain::SelectionView selectionViewFor(const geo::Camera& camera, double widthPx, double heightPx);
terrain::EyeView eyeViewFor(const geo::Camera& camera, double widthPx, double heightPx);

}  // namespace vegstream::scene
