// A still taken once the scene has settled at a pose (settled_still.h).

#include "app/settled_still.h"

#include <cmath>
#include <cstdio>

#include "scene/frame_driver.h"
#include "simulation/shared_code.h"

namespace vegstream::app {

std::string stillChanging(const scene::SceneFrameFigures& f, const scene::SceneFrameFigures& before) {
  std::string why;
  const auto add = [&](uint64_t n, const char* what) {
    if (n == 0) return;
    if (!why.empty()) why += ", ";
    why += std::to_string(n) + " " + what;
  };
  add(f.streaming.requestsIssued, "tile requests issued");
  add(f.streaming.requestsCompleted, "tiles arrived");
  add(f.uploads, "imagery uploads");
  add(f.terrain.roam.splits, "ROAM splits");
  add(f.terrain.roam.merges, "ROAM merges");
  add(f.terrain.roam.mergesStarted, "ROAM merge morphs started");
  add(f.terrain.roam.morphingVertices, "vertices morphing");
  add(f.terrain.roam.workLimited ? 1 : 0, "ROAM update cut by its work budget");
  // The selection itself moving (the error bound relaxing or recovering under the budgets).
  const auto moved = [&](double a, double b, const char* what) {
    if (a == b) return;
    if (!why.empty()) why += ", ";
    char buf[96];
    std::snprintf(buf, sizeof(buf), "%s %g → %g", what, a, b);
    why += buf;
  };
  moved(static_cast<double>(before.terrain.pieces), static_cast<double>(f.terrain.pieces), "pieces");
  moved(static_cast<double>(before.terrain.fallbackPieces), static_cast<double>(f.terrain.fallbackPieces),
        "fallback pieces");
  moved(before.terrain.relaxation, f.terrain.relaxation, "error bound relaxation");
  return why;
}

namespace {

// The still's frame again with the wind simulated simulationTimeS into a flight held at the
// pose: the still's image and record become that frame's.
Status stillAtSimulationTime(scene::FrameDriver& driver, const flight::FlightSample& pose, double timeS,
                             double simulationTimeS, SettledStill& still) {
  // The simulation's own steps, each as many fixed sub-steps as one step may run (a quarter
  // second): the sub-steps are counted from t = 0 whatever the steps' size
  // (simulation/simulation.h), so the state at S is the one a 60 fps flight reaches.
  const double chunkS = double(simulation::shader::kMaxSubsteps) / simulation::shader::kSubstepsPerS;
  const auto steps = static_cast<int>(std::floor(simulationTimeS / chunkS));
  scene::FrameInput input;
  input.pose = pose;
  input.timeS = timeS;
  input.sunTimeS = 0.0;
  for (int k = 1; k <= steps; ++k) {
    input.simulationTimeS = k * chunkS;
    if (Status s = driver.advanceSimulation(input); !s) return s.error();
  }
  input.simulationTimeS = simulationTimeS;
  input.readbackColor = true;
  auto frame = driver.run(input);
  if (!frame) return frame.error();
  if (frame->color) still.image = std::move(*frame->color);
  frame->color.reset();
  still.record = *frame;
  still.plants = frame->vegetation && frame->vegetation->gpuCounts ? frame->vegetation->plantsTotal : still.plants;
  return {};
}

}  // namespace

Result<SettledStill> renderSettledStill(scene::Scene& scene, const flight::FlightSample& pose, const Logger& log,
                                        int maxFrames, double simulationTimeS, bool aov) {
  scene::FrameDriver driver(scene);
  // A step of the fade time: whatever started to morph or fade in frame i is finished in i + 1.
  const double stepS = scene.options().terrain.fadeS;
  SettledStill still;
  scene::SceneFrameFigures before;
  for (int i = 0; i < maxFrames; ++i) {
    scene::FrameInput input;
    input.pose = pose;
    input.timeS = stepS * i;
    input.simulationTimeS = 0.0;
    input.sunTimeS = 0.0;
    input.readbackColor = true;
    auto frame = driver.run(input);
    if (!frame) return frame.error();
    still.frames = i + 1;
    // Frame 0 has nothing on screen to morph from (RoamMesh::markShown) but everything to load.
    still.unsettled = i == 0 ? std::string("the first frame") : stillChanging(frame->scene, before);
    before = frame->scene;
    still.settled = still.unsettled.empty();
    log->debug("still frame {} at t = {:.2f} s: {}", i, input.timeS, still.settled ? "settled" : still.unsettled);
    if (frame->color) still.image = std::move(*frame->color);
    frame->color.reset();
    still.record = *frame;
    still.terrainTriangles = frame->terrainTriangles;
    still.fallbackPieces = frame->scene.terrain.fallbackPieces;
    still.plantsCounted = frame->vegetation && frame->vegetation->gpuCounts;
    still.plants = still.plantsCounted ? frame->vegetation->plantsTotal : 0;
    if (still.settled) break;
  }
  scene::FrameInput last;  // the still's input: the AOV frame repeats it
  last.pose = pose;
  last.timeS = stepS * (still.frames - 1);
  last.simulationTimeS = 0.0;
  last.sunTimeS = 0.0;
  if (simulationTimeS > 0.0) {
    if (Status s = stillAtSimulationTime(driver, pose, last.timeS, simulationTimeS, still); !s) return s.error();
    last.simulationTimeS = simulationTimeS;
  }
  if (still.image.rgba.empty()) return makeError(ErrorKind::Internal, "the renderer returned no colour read-back");
  if (aov) {
    last.aov = true;
    auto frame = driver.run(last);
    if (!frame) return frame.error();
    if (!frame->aov) return makeError(ErrorKind::Internal, "the renderer returned no AOV read-back");
    still.aov = std::move(frame->aov);
  }
  return still;
}

}  // namespace vegstream::app
