// The frame driver (frame_driver.h): the fixed order of a frame, and the one place where the
// figures of its stages are gathered into a record.

#include "scene/frame_driver.h"

#include <algorithm>

#include <cmath>
#include <limits>
#include <string>

namespace vegstream::scene {

namespace {
constexpr double kNoFigure = std::numeric_limits<double>::quiet_NaN();
}

double FrameRecord::cpuMs() const {
  double ms = flightMs + scene.streamingMs + scene.terrainMs + scene.seedingMs + recordSubmitMs;
  if (!std::isnan(simulationMs)) ms += simulationMs;
  return ms;
}

FrameDriver::FrameDriver(Scene& scene) : FrameDriver(scene, scene.options().simulation) {}

FrameDriver::FrameDriver(Scene& scene, const simulation::SimulationOptions& simulation)
    : scene_(scene), simulation_(simulation) {}

void FrameDriver::simulate(const FrameInput& input, const glm::dvec3& camera) {
  const geo::LocalFrame& frame = scene_.frame();
  // The ground under a point, in the local frame; where the data has none, the point's own height.
  const auto groundZ = [&](const geo::Geodetic& g, double fallbackMsl) {
    const double h = scene_.groundHeight(g.latDeg, g.lonDeg);
    return frame.toLocal({g.latDeg, g.lonDeg, std::isnan(h) ? fallbackMsl : h}).z;
  };
  colliders_.clear();
  for (const flight::ColliderSample& c : input.colliders) {
    simulation::ColliderState s;
    s.centre = frame.toLocal(c.centre);
    s.radiusM = c.radiusM;
    s.lengthM = c.lengthM;
    s.groundZ = groundZ(c.centre, c.centre.heightM - 0.5 * c.lengthM - c.radiusM);
    colliders_.push_back(s);
  }
  sources_.clear();
  for (const flight::WindSourceSample& w : input.windSources) {
    simulation::WindSourceState s;
    s.type = w.type == flight::WindSourceSpec::Type::Fan         ? simulation::WindSourceType::Fan
             : w.type == flight::WindSourceSpec::Type::Whirlwind ? simulation::WindSourceType::Whirlwind
                                                                 : simulation::WindSourceType::Rotor;
    s.position = frame.toLocal(w.centre);
    s.groundZ = groundZ(w.centre, w.centre.heightM);
    s.radiusM = w.radiusM;
    s.strengthMps = w.strengthMps;
    s.directionDeg = w.directionDeg;
    sources_.push_back(s);
  }
  const double t = input.simulationTimeS.value_or(input.timeS);
  const double dt = lastStepS_ ? t - *lastStepS_ : 0.0;
  simulation_.step({t, dt, camera, colliders_, sources_});
  lastStepS_ = t;
}

Result<uint64_t> FrameDriver::submit(const FrameInput& input) {
  // The renderer would reuse the oldest frame's slot and overwrite its figures before they were
  // collected.
  if (inFlight_.size() >= kMaxInFlight)
    return makeError(ErrorKind::Internal, "frame driver: " + std::to_string(inFlight_.size()) +
                                              " frames in flight already; collect one before submitting another");
  // prepare: the pose's views once, then streaming, terrain, seeding and trees
  const FrameContext context = scene_.frameContext(input.pose, input.timeS, input.ahead);
  render::FrameRequest request = scene_.prepareFrame(context);
  const double sunTimeS = input.sunTimeS.value_or(input.timeS);
  if (input.sunTimeS) request.lighting = scene_.lightingAt(sunTimeS);
  request.lighting.adaptExposure = input.adaptExposure;
  // The window's exposure moves with the time between its frames (the first frame: none).
  if (input.adaptExposure && lastTimeS_) request.lighting.adaptSeconds = float(std::clamp(input.timeS - *lastTimeS_, 0.0, 1.0));
  lastTimeS_ = input.timeS;
  request.present = input.present;
  request.readbackColor = input.readbackColor;
  request.aov = input.aov;
  request.overlay = input.overlay;

  // simulate
  Stopwatch simulateWatch;
  simulate(input, context.camera.position);
  if (simulation_.simulates()) request.simulation = &simulation_.gpuStep();
  const double simulationMs = simulation_.simulates() ? simulateWatch.elapsedMs() : kNoFigure;

  // submit
  auto index = scene_.renderer().submitFrame(request);
  if (!index) return index.error();

  Stopwatch own;
  FrameRecord& r = inFlight_.emplace_back();
  r.index = *index;
  r.timeS = input.timeS;
  r.pose = input.pose;
  r.verticalFovDeg = context.camera.verticalFovDeg;
  r.datetime = scene_.sunClock().at(sunTimeS);
  r.sun = scene_.sunClock().sunAt(sunTimeS);
  r.flightMs = input.flightMs;
  r.scene = scene_.lastFrameFigures();  // the next prepare overwrites the scene's copy
  r.simulationMs = simulationMs;
  r.driverMs = own.elapsedMs();
  return *index;
}

Result<FrameRecord> FrameDriver::collect(uint64_t index) {
  // Oldest first: playback's rows and the window's HUD follow frame order, and the records
  // queue stays a queue.
  if (inFlight_.empty() || inFlight_.front().index != index)
    return makeError(ErrorKind::Internal,
                     "frame driver: collect(" + std::to_string(index) + ") refused: " +
                         (inFlight_.empty() ? std::string("no frame is in flight")
                                            : "frames are collected oldest first, next is " +
                                                  std::to_string(inFlight_.front().index)));
  auto result = scene_.renderer().waitFrame(index);
  FrameRecord r = std::move(inFlight_.front());
  inFlight_.pop_front();
  if (!result) return result.error();

  // collect
  Stopwatch own;
  r.recordSubmitMs = result->cpuRecordMs;
  r.gpu = std::move(result->gpu);
  r.terrainTriangles = result->terrainTriangles;
  r.terrainRasterised = result->terrainRasterised;
  r.terrainRasterTriangles = result->terrainRasterTriangles;
  r.terrainTileEntries = result->terrainTileEntries;
  r.terrainTileEntriesDropped = result->terrainTileEntriesDropped;
  r.vegetation = result->vegetation;
  r.trees = result->trees;
  r.color = std::move(result->color);
  r.aov = std::move(result->aov);
  r.exposureEv = result->exposureEv;
  r.driverMs += own.elapsedMs();
  return r;
}

Status FrameDriver::advanceSimulation(const FrameInput& input) {
  if (!inFlight_.empty())
    return makeError(ErrorKind::Internal, "frame driver: advanceSimulation() with " +
                                              std::to_string(inFlight_.size()) + " frames in flight; collect them first");
  const FrameContext context = scene_.frameContext(input.pose, input.timeS);
  simulate(input, context.camera.position);
  render::FrameRequest request = scene_.cameraRequest(context);
  if (!simulation_.simulates()) return {};
  request.simulation = &simulation_.gpuStep();
  auto index = scene_.renderer().submitFrame(request);
  if (!index) return index.error();
  auto done = scene_.renderer().waitFrame(*index);
  if (!done) return done.error();
  return {};
}

Result<FrameRecord> FrameDriver::run(const FrameInput& input) {
  if (!inFlight_.empty())
    return makeError(ErrorKind::Internal, "frame driver: run() with " + std::to_string(inFlight_.size()) +
                                              " frames in flight; collect them first");
  auto index = submit(input);
  if (!index) return index.error();
  return collect(*index);
}

}  // namespace vegstream::scene
