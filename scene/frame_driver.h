#pragma once
// The one frame driver. Every mode that draws frames — the window, headless `fly` and `record`
// — runs each frame through it: the pose becomes the frame's context (frame_context.h: its views,
// once), then the list of stages (frame_stage.h) runs over it in one fixed order:
//
//   streaming, terrain, seeding, trees   the scene's (Scene::prepareFrame): wanted tiles,
//             streaming (settled or realtime), ROAM, the terrain's draws, the seed triangles, trees
//   simulation  the shared simulation's step at the frame's time (simulation_stage.h)
//   render    the renderer records and submits the frame's commands (render_stage.h)
//
// and collect() waits for the GPU and gathers the figures of every stage into one FrameRecord.
//
// submit() and collect() are separate so the CPU prepares the next frames while the GPU draws
// the earlier ones: the window and fixed-step playback (playback.h) submit frame n + 1 (and
// n + 2) before collecting frame n, so a frame's wall time comes close to max(CPU, GPU) rather
// than their sum. run() is both at once, the serial way.
//
// Pipelining changes no figure but the timings: nothing a frame's CPU stages do reads a GPU
// result of an earlier frame (the GPU's counts and read-backs only go into that frame's record),
// so the scene sees the same calls in the same order whatever the depth.
//
// Contract: at most kMaxInFlight frames are in flight (the renderer's frame slots); collect()
// takes the index that submit() returned, oldest first. Breaking either — a submit beyond the
// slots, a collect out of order or of an unknown frame, run() with frames in flight — is refused
// with an ErrorKind::Internal error that changes nothing (a caller bug, testable in release
// builds). GPU failures come back as errors.

#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <vector>

#include "core/result.h"
#include "core/stopwatch.h"
#include "flight/path_sampler.h"
#include "render/frame_slots.h"
#include "render/frame_types.h"
#include "scene/frame_input.h"
#include "scene/render_stage.h"
#include "scene/scene.h"
#include "scene/simulation_stage.h"
#include "simulation/simulation.h"

namespace vegstream::scene {

// One frame's figures from every stage; NaN (kNoFigure) where a figure does not exist.
struct FrameRecord {
  uint64_t index = 0;  // the renderer's frame index
  double timeS = 0.0;
  flight::FlightSample pose;
  double verticalFovDeg = 0.0;  // the camera's
  geo::DateTime datetime;       // the sun's date-time (Scene::sunClock at sunTimeS or timeS)
  geo::SolarPosition sun;       // seen from the dataset's centre at `datetime`
  float exposureEv = 0.0f;      // EV100 the frame was tone-mapped with (render::FrameResult)
  double flightMs = 0.0;        // FrameInput::flightMs
  SceneFrameFigures scene;      // prepare: streaming, terrain, seeding
  double simulationMs = 0.0;    // NaN while the simulation does nothing (SimulationOptions::enabled off)
  double recordSubmitMs = 0.0;  // the renderer's own timer
  render::GpuTimings gpu;
  uint64_t terrainTriangles = 0;
  uint64_t terrainChunksDrawn = 0, terrainChunksUploaded = 0, terrainVerticesUploaded = 0;  // render::FrameResult's
  bool terrainRasterised = false;  // in compute (render::FrameResult::terrainRasterised): the next three exist
  uint64_t terrainRasterTriangles = 0, terrainTileEntries = 0, terrainTileEntriesDropped = 0;
  uint64_t terrainDepthTiles = 0, terrainDepthEdgeTiles = 0;
  std::optional<render::VegetationFigures> vegetation;
  std::optional<render::TreeFigures> trees;  // when the frame drew trees
  std::optional<render::ColorImage> color;  // when FrameInput::readbackColor
  std::optional<render::AovImage> aov;      // when FrameInput::aov
  double driverMs = 0.0;                    // the driver's own bookkeeping (copying figures)
  double cpuMs() const;                     // the CPU stages that exist: flight … record/submit
  // The recorder's (playback.h), for a recorded frame: its row, its wall time, its own bookkeeping
  // and the PNG writing (NaN: not saved). NaN outside a recording.
  std::size_t row = 0;
  double wallMs = std::numeric_limits<double>::quiet_NaN();
  double recorderMs = std::numeric_limits<double>::quiet_NaN();
  double pngMs = std::numeric_limits<double>::quiet_NaN();
};

class FrameDriver {
 public:
  static constexpr std::size_t kMaxInFlight = render::kFramesInFlight;

  // The simulation runs with the scene's SimulationOptions, or `simulation` where given.
  explicit FrameDriver(Scene& scene);
  FrameDriver(Scene& scene, const simulation::SimulationOptions& simulation);

  // prepare → simulate → submit. Does not wait for the GPU. Refused when kMaxInFlight frames
  // are in flight (collect one first).
  Result<uint64_t> submit(const FrameInput& input);
  // Waits for the oldest frame in flight (`index`, as submit() returned it) and returns its
  // record. Any other index is refused (nothing is waited for or dropped).
  Result<FrameRecord> collect(uint64_t index);
  // submit + collect; refused while frames are in flight.
  Result<FrameRecord> run(const FrameInput& input);
  // Only the simulation's step for `input` (no terrain, plants or read-back: the GPU runs the
  // step and nothing else is drawn), waited for; refused while frames are in flight. Lets a still
  // show the simulation S seconds in without drawing S × 60 whole frames.
  Status advanceSimulation(const FrameInput& input);
  const simulation::Simulation& simulation() const { return simulation_.simulation(); }
  // The wind from the next frame on (the window sets it from the HUD).
  void setWind(const simulation::WindOptions& wind) { simulation_.simulation().setWind(wind); }

  std::size_t framesInFlight() const { return inFlight_.size(); }
  // The index collect() takes next; 0 when nothing is in flight.
  uint64_t oldestInFlight() const { return inFlight_.empty() ? 0 : inFlight_.front().index; }
  Scene& scene() { return scene_; }

 private:
  Scene& scene_;
  // The frame's list of stages: the scene's (streaming, terrain, seeding, trees:
  // Scene::prepareFrame), then these two.
  SimulationStage simulation_;
  RenderStage render_;
  std::deque<FrameRecord> inFlight_;  // submitted, not collected (≤ kMaxInFlight), oldest first
};

}  // namespace vegstream::scene
