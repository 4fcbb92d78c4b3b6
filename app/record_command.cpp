// `vegstream record` (record_command.h).

#include "app/record_command.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "app/sample_dataset.h"
#include "core/atomic_file.h"
#include "datasets/dataset_format.h"
#include "flight/flight_path_json.h"
#include "flight/recorder.h"
#include "flight/report.h"
#include "flight/scene.h"
#include "flight/summary.h"
#include "streaming/open_tile_source.h"
#include "vegetation/species_catalog.h"

namespace vegstream::app {
namespace fs = std::filesystem;

bool parseFrameSize(const std::string& text, uint32_t& w, uint32_t& h) {
  static const std::regex re(R"((\d{1,6})[xX](\d{1,6}))");
  std::smatch m;
  if (!std::regex_match(text, m, re)) return false;
  w = static_cast<uint32_t>(std::stoul(m[1]));
  h = static_cast<uint32_t>(std::stoul(m[2]));
  return w >= 1 && h >= 1 && w <= 16384 && h <= 16384;
}

CLI::App* addRecordCommand(CLI::App& cli, RecordOptions& o) {
  auto* cmd = cli.add_subcommand("record", "Fly a path at a fixed time step and record per-frame figures, summary and plots");
  cmd->add_option("dataset", o.dataset,
                  "Dataset directory (vegstream import) or http(s):// URL of one; default: the Zion sample");
  cmd->add_option("--path", o.path, "Flight path JSON (vegstream path makes one for any dataset)")->required();
  cmd->add_option("--out", o.out, "Recording directory to create (must not exist or be empty)")->required();
  cmd->add_option("--size", o.size, "Frame size WxH")->capture_default_str();
  cmd->add_option("--msaa", o.msaa, "Samples per pixel (1, 2, 4, 8, 16 where the device offers them)")->capture_default_str();
  cmd->add_option("--fps", o.fps, "Frames per second of flight time (the fixed step)")->capture_default_str()
      ->check(CLI::Range(1.0, 1000.0));
  cmd->add_option("--frames-every", o.framesEvery, "Save every K-th frame as frames/frame_NNNNN.png (0: none)")
      ->capture_default_str()->check(CLI::Range(0, 1000000));
  cmd->add_option("--warmup", o.warmupS, "Seconds of frames rendered at the start before recording")
      ->capture_default_str()->check(CLI::Range(0.0, 600.0));
  cmd->add_option("--device", o.device, "Use the GPU whose name contains NAME (see `vegstream devices`)");
  cmd->add_flag("--validate", o.validate, "Turn on the Vulkan validation layers");
  cmd->add_flag("--no-plots", o.noPlots, "Write frames.csv and the JSON files only (no python3/matplotlib needed)");
  addStreamingOptions(*cmd, o.streaming, true);
  return cmd;
}

namespace {

Status writeText(const fs::path& file, const std::string& text) {
  std::ofstream f(file, std::ios::binary);
  f << text;
  return f ? Status{} : makeError(ErrorKind::Io, "cannot write " + file.string());
}

}  // namespace

int runRecord(const RecordOptions& o, const Logger& log) {
  auto userError = [&](const std::string& m) { return reportError(log, makeError(ErrorKind::InvalidInput, m)); };
  uint32_t width = 0, height = 0;
  if (!parseFrameSize(o.size, width, height))
    return userError("--size " + o.size + ": expected WxH with each side 1 … 16384, e.g. 640x360");
  if (o.msaa != 1 && o.msaa != 2 && o.msaa != 4 && o.msaa != 8 && o.msaa != 16)
    return userError("--msaa " + std::to_string(o.msaa) + ": samples per pixel must be 1, 2, 4, 8 or 16");
  std::error_code ec;
  if (fs::exists(o.out, ec) && !(fs::is_directory(o.out, ec) && fs::is_empty(o.out, ec)))
    return userError("--out " + o.out + " already exists and is not empty; choose another output directory");

  auto path = flight::loadFlightPath(o.path);
  if (!path) return reportError(log, path.error());

  flight::SceneOptions so;
  if (Status s = applyStreamingOptions(o.streaming, flight::StreamingMode::Settled, so); !s)
    return reportError(log, s.error());
  std::string dataset = o.dataset;
  if (dataset.empty()) {
    auto sample = ensureZionSample(o.samplesDir, "out/datasets/zion", log);
    if (!sample) return reportError(log, sample.error());
    dataset = sample->string();
  }
  const bool remote = streaming::isHttpLocation(dataset);
  if (!remote) {  // a local dataset is checked against the path before the GPU is touched
    auto meta = datasets::readDatasetMeta(dataset);
    if (!meta) return reportError(log, meta.error());
    if (Status s = flight::checkInside(*path, meta->bounds); !s)
      return userError(o.path + ": " + s.error().message);
  }

  so.dataset = dataset;
  so.renderer.width = width;
  so.renderer.height = height;
  so.renderer.msaa = o.msaa;
  so.renderer.context.deviceName = o.device;
  so.renderer.context.validate = o.validate;
  so.renderer.context.validationLog = std::make_shared<render::ValidationLog>();
  so.renderer.context.validationLog->setListener([log](const std::string& m, bool isError) {
    if (isError) log->error("validation: {}", m); else log->warn("validation: {}", m);
  });
  auto scene = flight::Scene::open(so);
  if (!scene) return reportError(log, scene.error());
  if (Status s = flight::checkInside(*path, (*scene)->info().bounds); !s) return userError(o.path + ": " + s.error().message);
  const render::DeviceInfo& dev = (*scene)->renderer().device();
  log->info("device: {} ({}, {}, Vulkan {}, MSAA {})", dev.name, dev.type, dev.driver, dev.apiVersion, o.msaa);
  const flight::SceneInfo& info = (*scene)->info();
  log->info("dataset {} from {}: zooms {}…{}, {} streaming{}, budgets CPU {:.0f} MiB, GPU {:.0f} MiB ({:.0f} ms)",
            info.datasetName, info.source, info.minZoom, info.maxZoom, toString(so.mode),
            so.lookAhead ? " with look-ahead" : " without look-ahead", o.streaming.cpuBudgetMb,
            o.streaming.gpuBudgetMb, info.loadMs);
  const std::size_t total = flight::frameCount(path->duration(), o.fps);
  log->info("recording {} ({:.1f} s) at {} fps: {} frames of {}x{}", path->name, path->duration(), o.fps, total, width,
            height);

  flight::Recording recording;
  std::optional<Error> plotError;
  const Status written = writeDirectoryAtomically(o.out, [&](const fs::path& tmp) -> Status {
    flight::RecorderOptions ro;
    ro.fps = o.fps;
    ro.warmupS = o.warmupS;
    ro.framesEvery = o.framesEvery;
    ro.framesDir = tmp / flight::kFramesDir;
    std::size_t nextReport = total / 10;
    ro.progress = [&](std::size_t done, std::size_t all) {
      if (done < nextReport || done == all) return;
      log->info("  {} / {} frames", done, all);
      nextReport += std::max<std::size_t>(all / 10, 1);
    };
    auto rec = flight::recordFlight(**scene, *path, ro);
    if (!rec) return rec.error();
    recording = std::move(*rec);

    flight::RecordingMeta m;
    m.device = dev;
    m.width = width;
    m.height = height;
    m.msaa = o.msaa;
    m.fps = o.fps;
    m.warmupS = o.warmupS;
    m.warmupFrames = recording.warmupFrames;
    m.framesEvery = o.framesEvery;
    m.pathName = path->name;
    m.pathFile = fs::absolute(o.path).lexically_normal().string();
    m.pathDurationS = path->duration();
    m.datasetName = info.datasetName;
    m.datasetDir = remote ? dataset : fs::absolute(dataset).lexically_normal().string();
    m.datasetSource = info.source;
    m.heightZoom = info.maxZoom;
    m.imageryZoom = info.hasImagery ? info.maxZoom : -1;
    m.groundZoom = info.groundZoom;
    m.sceneLoadMs = info.loadMs;
    m.streaming.mode = toString(so.mode);
    m.streaming.lookAhead = so.lookAhead;
    m.streaming.cpuBudgetBytes = so.streaming.cpuBudgetBytes;
    m.streaming.gpuBudgetBytes = so.streaming.gpuBudgetBytes;
    m.streaming.uploadBytesPerFrame = so.streaming.uploadBytesPerFrame;
    m.streaming.maxRequestsInFlight = so.streaming.maxRequestsInFlight;
    m.streaming.imageryLayers = info.imageryLayers;
    m.streaming.terrainErrorPx = so.terrain.maxErrorPx;
    m.streaming.terrainMaxNodes = so.terrain.maxNodes;
    m.streaming.terrainMaxTriangles = so.terrain.roam.maxTriangles;
    m.streaming.canopyM = so.terrain.roam.canopyM;
    m.streaming.seedHorizonM = so.terrain.seeds.horizonM;
    m.streaming.seedLevel = info.seedLevel;
    m.streaming.seedTriangleAreaM2 = info.seedAreaM2;
    m.plants.enabled = so.plants;
    m.plants.density = so.terrain.seeds.density;
    m.plants.maxPerTriangle = so.terrain.seeds.maxPlants;
    m.plants.clusterSize = so.clusterSize;
    m.plants.speciesCatalog = o.streaming.species.empty() ? "default" : o.streaming.species;
    m.plants.style = o.streaming.plantStyle;
    m.plants.maxSegments = so.plantDraw.maxSegments;
    m.plants.lodDistanceM = so.plantDraw.lodDistanceM;
    m.plants.shadows = so.plantDraw.shadows;
    for (const vegetation::Species& s : (so.species ? *so.species : vegetation::defaultSpeciesCatalog()).species)
      m.plants.species.push_back(s.name);
    m.validate = o.validate;
    m.validationErrors = so.renderer.context.validationLog->errors();
    m.validationWarnings = so.renderer.context.validationLog->warnings();
    m.perPassMeaningful = recording.perPassMeaningful;
    m.pipelineStatistics = recording.pipelineStatistics;
    m.gpuPasses = recording.gpuPasses;
    m.wallS = recording.wallS;
    m.peakRssBytes = recording.peakRssBytes;
    if (Status s = writeText(tmp / flight::kFramesCsv, recording.table.toCsv()); !s) return s;
    if (Status s = writeText(tmp / flight::kRecordingJson, flight::recordingMetaJson(m)); !s) return s;
    if (Status s = flight::writeSummary(tmp); !s) return s;
    if (!o.noPlots)
      if (Status s = flight::makePlots(tmp, flight::defaultPythons()); !s) plotError = s.error();
    return {};
  });
  if (!written) return reportError(log, written.error());

  const auto& t = recording.table;
  const auto gpu = t.values(*t.find("gpu_frame_ms")), cpu = t.values(*t.find("cpu_frame_ms"));
  const auto rec = t.values(*t.find("recorder_ms"));
  double cpuSum = 0.0, recSum = 0.0;
  for (double v : cpu) cpuSum += v;
  for (double v : rec) recSum += v;
  log->info("{} frames in {:.1f} s wall; GPU frame p50 {:.2f} ms, p95 {:.2f} ms; recorder {:.2f} % of the CPU frame",
            t.rowCount(), recording.wallS, flight::percentile(gpu, 50), flight::percentile(gpu, 95),
            cpuSum > 0.0 ? 100.0 * recSum / cpuSum : 0.0);
  if (dev.software) log->info("{} is a CPU rasteriser: per-pass GPU times are left empty", dev.name);
  if (so.renderer.context.validationLog->errors() > 0)
    log->error("validation reported {} errors", so.renderer.context.validationLog->errors());
  log->info("written to {}", o.out);
  if (plotError) {
    log->error("{}", plotError->message);
    return kExitFailure;
  }
  return so.renderer.context.validationLog->errors() > 0 ? kExitFailure : kExitOk;
}

}  // namespace vegstream::app
