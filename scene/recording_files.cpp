// The recording directory (recording_files.h).

#include "scene/recording_files.h"

#include <fstream>

#include "core/atomic_file.h"
#include "flight/report.h"
#include "streaming/open_tile_source.h"
#include "vegetation/species_catalog.h"

namespace vegstream::scene {
namespace fs = std::filesystem;

namespace {

Status writeText(const fs::path& file, const std::string& text) { return writeTextAtomically(file, text); }

const char* styleName(render::PlantStyle style) {
  switch (style) {
    case render::PlantStyle::Plants: return "plants";
    case render::PlantStyle::Markers: return "markers";
    case render::PlantStyle::Hidden: return "hidden";
  }
  return "plants";
}

// recording.json's streaming and terrain settings.
flight::RecordingMeta::Streaming streamingMeta(const SceneOptions& so, const SceneInfo& info) {
  flight::RecordingMeta::Streaming streaming;
  streaming.mode = toString(so.mode);
  streaming.lookAhead = so.lookAhead;
  streaming.cpuBudgetBytes = so.streaming.cpuBudgetBytes;
  streaming.gpuBudgetBytes = so.streaming.gpuBudgetBytes;
  streaming.uploadBytesPerFrame = so.streaming.uploadBytesPerFrame;
  streaming.maxRequestsInFlight = so.streaming.maxRequestsInFlight;
  streaming.imageryLayers = info.imageryLayers;
  streaming.terrainErrorPx = so.terrain.maxErrorPx;
  streaming.terrainMaxNodes = so.terrain.maxNodes;
  streaming.terrainMaxTriangles = so.terrain.roam.maxTriangles;
  streaming.canopyM = so.terrain.roam.canopyM;
  streaming.terrainDetail = so.terrainDetail;
  streaming.seedHorizonM = so.terrain.seeds.horizonM;
  streaming.seedLevel = info.seedLevel;
  streaming.seedTriangleAreaM2 = info.seedAreaM2;
  return streaming;
}

// recording.json's plant settings: those asked for, and the blade path the device gave.
flight::RecordingMeta::Plants plantsMeta(const SceneOptions& so, const render::Renderer& r,
                                         const std::string& speciesCatalog) {
  flight::RecordingMeta::Plants plants;
  plants.enabled = so.plants;
  plants.density = so.terrain.seeds.density;
  plants.maxPerTriangle = so.terrain.seeds.maxPlants;
  plants.groundDensityM2 = so.terrain.seeds.groundDensityM2;
  plants.clusterSize = so.clusterSize;
  plants.speciesCatalog = speciesCatalog;
  plants.style = so.plantDraw.flatColour ? "coverage" : styleName(so.plantStyle);
  plants.maxSegments = so.plantDraw.maxSegments;
  plants.lodDistanceM = so.plantDraw.lodDistanceM;
  plants.shadows = so.plantDraw.shadows;
  plants.shadowDistanceM = so.plantDraw.shadowDistanceM;
  plants.fades = so.plantDraw.fades;
  plants.occlusionCulling = so.occlusionCulling;
  plants.bladePath = render::bladePathName(r.bladePath());
  plants.bladePathRequested = render::bladePathName(so.renderer.bladePath);
  for (const vegetation::Species& s : (so.species ? *so.species : vegetation::defaultSpeciesCatalog()).species)
    plants.species.push_back(s.name);
  return plants;
}

}  // namespace

flight::RecordingMeta recordingMeta(const Scene& scene, const flight::FlightPath& path, const Recording& recording,
                                    const RecordingRequest& request) {
  const SceneOptions& so = scene.options();
  const SceneInfo& info = scene.info();
  const render::DeviceInfo& dev = scene.renderer().device();
  const render::Renderer& r = scene.renderer();
  flight::RecordingMeta m;
  m.device = {dev.name, dev.type, dev.driver, dev.apiVersion, dev.software};
  m.width = r.width();
  m.height = r.height();
  m.msaa = r.msaa();
  m.terrainShading = render::terrainShadingName(r.terrainShading());
  m.fps = request.playback.fps;
  m.warmupS = request.playback.warmupS;
  m.warmupFrames = recording.warmupFrames;
  m.framesEvery = request.playback.framesEvery;
  m.framesInFlight = static_cast<int>(recording.framesInFlight);
  m.pathName = path.name;
  m.pathFile = request.pathFile.empty() ? "" : fs::absolute(request.pathFile).lexically_normal().string();
  m.pathDurationS = path.duration();
  m.datasetName = info.datasetName;
  m.datasetDir =
      streaming::isHttpLocation(so.dataset) ? so.dataset : fs::absolute(so.dataset).lexically_normal().string();
  m.datasetSource = info.source;
  m.heightZoom = info.maxZoom;
  m.imageryZoom = info.hasImagery ? info.maxZoom : -1;
  m.groundZoom = info.groundZoom;
  m.sceneLoadMs = info.loadMs;
  m.streaming = streamingMeta(so, info);
  m.plants = plantsMeta(so, r, request.speciesCatalog);
  const SunClock& sun = scene.sunClock();
  const geo::SolarPosition start = sun.sunAt(0.0);
  m.sun.datetime = geo::formatIsoDateTime(sun.start);
  m.sun.datetimeSource = toString(sun.source);
  m.sun.latDeg = sun.latDeg;
  m.sun.lonDeg = sun.lonDeg;
  m.sun.azimuthDeg = start.azimuthDeg;
  m.sun.elevationDeg = start.elevationDeg;
  if (so.exposureEv) m.exposureEv = *so.exposureEv;
  m.validate = so.renderer.context.validate;
  if (const render::ValidationLog* v = r.validationLog()) {
    m.validationErrors = static_cast<uint64_t>(v->errors());
    m.validationWarnings = static_cast<uint64_t>(v->warnings());
  }
  m.perPassMeaningful = recording.perPassMeaningful;
  m.pipelineStatistics = recording.pipelineStatistics;
  m.gpuPasses = recording.gpuPasses;
  m.wallS = recording.wallS;
  m.peakRssBytes = recording.peakRssBytes;
  return m;
}

Result<RecordingOutcome> recordToDirectory(FrameDriver& driver, const flight::FlightPath& path,
                                           const RecordingRequest& request) {
  RecordingOutcome outcome;
  const Status written = writeDirectoryAtomically(request.out, [&](const fs::path& tmp) -> Status {
    PlaybackOptions po = request.playback;
    po.framesDir = tmp / flight::kFramesDir;
    if (po.framesEvery > 0) {
      std::error_code ec;
      fs::create_directories(po.framesDir, ec);
      if (ec) return makeError(ErrorKind::Io, "cannot create " + po.framesDir.string() + ": " + ec.message());
    }
    auto rec = playFlight(driver, path, po);
    if (!rec) return rec.error();
    outcome.recording = std::move(*rec);
    const flight::RecordingMeta meta = recordingMeta(driver.scene(), path, outcome.recording, request);
    if (Status s = writeText(tmp / flight::kFramesCsv, outcome.recording.table.toCsv()); !s) return s;
    if (Status s = writeText(tmp / flight::kRecordingJson, flight::recordingMetaJson(meta)); !s) return s;
    if (Status s = flight::writeSummary(tmp); !s) return s;
    if (request.plots)
      if (Status s = flight::makePlots(tmp, flight::defaultPythons()); !s) outcome.plotError = s.error();
    return {};
  });
  if (!written) return written.error();
  return outcome;
}

}  // namespace vegstream::scene
