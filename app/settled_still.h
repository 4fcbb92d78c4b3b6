#pragma once
// One still frame at a fixed pose, taken only once the scene has settled there (`vegstream
// snapshot`): frames are run through the frame driver at the same pose, flight time advancing
// by the terrain's fade time (StreamedTerrainOptions::fadeS) each frame, until one frame (not the
// first) changes nothing — no tile requested, arrived or uploaded, no ROAM split, merge or merge
// morph, no vertex still morphing, the queue work not cut short, the pieces, their fallbacks and
// the error bound's relaxation as in the frame before — and that frame is the still. Pieces
// drawn from coarser tiles (fallbacks) that stay do not keep it from settling: with nothing
// requested any more they are what the budgets allow; fallbackPieces says how many there are. Settled streaming (SceneOptions::mode) makes every frame wait for the tiles it wants,
// so the finest tiles the view needs are drawn; advancing time by fadeS finishes the geomorphs
// that a split starts after the first drawn frame (RoamMesh::markShown) and the imagery fades
// of tiles that arrived a frame before. Deterministic: the same inputs give the same frames,
// and on the same driver the same pixels.

#include <cstdint>
#include <optional>
#include <string>

#include "core/log.h"
#include "core/result.h"
#include "flight/path_sampler.h"
#include "render/frame_types.h"
#include "scene/frame_driver.h"
#include "scene/scene.h"

namespace vegstream::app {

struct SettledStill {
  render::ColorImage image;
  int frames = 0;          // frames run, the still included
  bool settled = false;    // false: maxFrames ran out; the last frame is the still
  std::string unsettled;   // what still changed in the last frame (when !settled)
  bool plantsCounted = false;
  uint64_t plants = 0;     // plants drawn in the still (read back from the GPU)
  uint64_t terrainTriangles = 0;
  uint64_t fallbackPieces = 0;  // pieces of the still drawn from an ancestor's tiles (0: the finest wanted)
  scene::FrameRecord record;    // the still's figures, its sun and exposure (its colour is `image`)
  std::optional<render::AovImage> aov;  // with `aov`: the still's AOVs (scene/frame_aovs.h)
};

// Runs frames at `pose` (the scene should stream settled) until one changes nothing, at most
// maxFrames; each frame's changes are logged at debug level (-v). GPU failures come back as errors.
// The sun is the scene's at flight time 0 in every frame (FrameInput::sunTimeS): the still shows
// the date-time it was asked for, however many frames it took to settle.
// With simulationTimeS > 0 the settle frames hold the simulation at time 0; then the simulation
// alone (scene::FrameDriver::advanceSimulation) runs in quarter-second steps of its fixed
// sub-steps to simulationTimeS — the same sub-steps a 60 fps flight runs — and one more frame at
// the settled scene is the still.
// With `aov` one more frame at the still's pose and times, an AOV frame (render/aov_image.h),
// gives SettledStill::aov: nothing has changed since the still, so it shows the same scene.
Result<SettledStill> renderSettledStill(scene::Scene& scene, const flight::FlightSample& pose, const Logger& log,
                                        int maxFrames = 40, double simulationTimeS = 0.0, bool aov = false);

// What a frame's figures say still changed, given the frame before's ("" when nothing).
std::string stillChanging(const scene::SceneFrameFigures& figures, const scene::SceneFrameFigures& before);

}  // namespace vegstream::app
