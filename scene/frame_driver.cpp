// The frame driver (frame_driver.h): the fixed order of a frame, and the one place where the
// figures of its stages are gathered into a record.

#include "scene/frame_driver.h"

#include <cmath>
#include <string>

namespace vegstream::scene {

double FrameRecord::cpuMs() const {
  double ms = flightMs + scene.streamingMs + scene.terrainMs + scene.seedingMs + recordSubmitMs;
  if (!std::isnan(simulationMs)) ms += simulationMs;
  return ms;
}

FrameDriver::FrameDriver(Scene& scene) : FrameDriver(scene, scene.options().simulation) {}

FrameDriver::FrameDriver(Scene& scene, const simulation::SimulationOptions& simulation)
    : scene_(scene), simulation_(scene, simulation), render_(scene) {}

Result<uint64_t> FrameDriver::submit(const FrameInput& input) {
  // The renderer would reuse the oldest frame's slot and overwrite its figures before they were
  // collected.
  if (inFlight_.size() >= kMaxInFlight)
    return makeError(ErrorKind::Internal, "frame driver: " + std::to_string(inFlight_.size()) +
                                              " frames in flight already; collect one before submitting another");
  FrameContext context = scene_.frameContext(input.pose, input.timeS, input.ahead);
  context.input = &input;
  scene_.prepareFrame(context);  // streaming, terrain, seeding, trees
  simulation_.run(context);
  render_.run(context);
  if (!*context.submitted) return context.submitted->error();
  const uint64_t index = **context.submitted;

  Stopwatch own;
  FrameRecord& r = inFlight_.emplace_back();
  r.index = index;
  r.timeS = input.timeS;
  r.pose = input.pose;
  r.verticalFovDeg = context.camera.verticalFovDeg;
  const double sunTimeS = input.sunTimeS.value_or(input.timeS);
  r.datetime = scene_.sunClock().at(sunTimeS);
  r.sun = scene_.sunClock().sunAt(sunTimeS);
  r.flightMs = input.flightMs;
  r.scene = context.figures;
  r.simulationMs = context.simulationMs;
  r.driverMs = own.elapsedMs();
  return index;
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
  r.terrainChunksDrawn = result->terrainChunksDrawn;
  r.terrainChunksUploaded = result->terrainChunksUploaded;
  r.terrainVerticesUploaded = result->terrainVerticesUploaded;
  r.terrainRasterised = result->terrainRasterised;
  r.terrainRasterTriangles = result->terrainRasterTriangles;
  r.terrainTileEntries = result->terrainTileEntries;
  r.terrainTileEntriesDropped = result->terrainTileEntriesDropped;
  r.terrainDepthTiles = result->terrainDepthTiles;
  r.terrainDepthEdgeTiles = result->terrainDepthEdgeTiles;
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
  FrameContext context = scene_.frameContext(input.pose, input.timeS);
  context.input = &input;
  simulation_.run(context);
  if (!context.request.simulation) return {};
  render::FrameRequest request = scene_.cameraRequest(context);
  request.simulation = context.request.simulation;
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
