// `vegstream record` (record_command.h).

#include "app/record_command.h"

#include <cmath>
#include <filesystem>
#include <regex>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "app/scene_setup.h"
#include "datasets/dataset_format.h"
#include "flight/flight_path_json.h"
#include "render/frame_slots.h"
#include "scene/frame_aovs.h"
#include "streaming/open_tile_source.h"

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

void addFramesInFlightOption(CLI::App& cmd, int& framesInFlight) {
  cmd.add_option("--frames-in-flight", framesInFlight,
                 "Frames the CPU prepares while the GPU draws, 1 … " + std::to_string(render::kFramesInFlight) +
                     " (1: one frame at a time, the wall time is CPU + GPU)")
      ->capture_default_str()
      ->check(CLI::Range(1, render::kFramesInFlight));
}

CLI::App* addRecordCommand(CLI::App& cli, RecordOptions& o) {
  auto* cmd =
      cli.add_subcommand("record", "Fly a path at a fixed time step and record per-frame figures, summary and plots");
  cmd->add_option("dataset", o.dataset,
                  "Dataset directory (vegstream import) or http(s):// URL of one; default: the Zion sample");
  cmd->add_option("--path", o.path, "Flight path JSON (vegstream path makes one for any dataset)")->required();
  cmd->add_option("--out", o.out, "Recording directory to create (must not exist or be empty)")->required();
  cmd->add_option("--size", o.size, "Frame size WxH")->capture_default_str();
  cmd->add_option("--msaa", o.msaa, "Samples per pixel (1, 2, 4, 8, 16 where the device offers them)")
      ->capture_default_str();
  cmd->add_option("--fps", o.fps, "Frames per second of flight time (the fixed step)")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1000.0));
  cmd->add_option("--frames-every", o.framesEvery, "Save every K-th frame as frames/frame_NNNNN.png (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--aov", o.aov,
                  "With --frames-every: also write each saved frame's measurement AOVs, comma-separated out of "
                  "depth, coverage, species (frame_NNNNN.depth.tif …; an extra frame each, its time not counted)");
  addFramesInFlightOption(*cmd, o.framesInFlight);
  cmd->add_option("--warmup", o.warmupS, "Seconds of frames rendered at the start before recording")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 600.0));
  cmd->add_option("--device", o.device, "Use the GPU whose name contains NAME (see `vegstream devices`)");
  cmd->add_flag("--validate", o.validate, "Turn on the Vulkan validation layers");
  cmd->add_flag("--no-plots", o.noPlots, "Write frames.csv and the JSON files only (no python3/matplotlib needed)");
  addSceneOptions(*cmd, o.streaming, true, o.simulationCli, o.treeCli, o.sunCli);
  return cmd;
}

int runRecord(RecordOptions o, const Logger& log) {
  auto userError = [&](const std::string& m) { return reportError(log, makeError(ErrorKind::InvalidInput, m)); };
  uint32_t width = 0, height = 0;
  if (!parseFrameSize(o.size, width, height))
    return userError("--size " + o.size + ": expected WxH with each side 1 … 16384, e.g. 640x360");
  if (o.msaa != 1 && o.msaa != 2 && o.msaa != 4 && o.msaa != 8 && o.msaa != 16)
    return userError("--msaa " + std::to_string(o.msaa) + ": samples per pixel must be 1, 2, 4, 8 or 16");
  if (Status s = checkSimulationOptions(o.simulationCli); !s) return reportError(log, s.error());
  auto sun = checkSunOptions(o.sunCli);
  if (!sun) return reportError(log, sun.error());
  auto aovs = scene::parseAovList(o.aov);
  if (!aovs) return reportError(log, aovs.error());
  if (aovs->any() && o.framesEvery <= 0)
    return userError("--aov " + o.aov +
                     ": --frames-every K is required (the AOVs are written beside the saved frames)");
  std::error_code ec;
  if (fs::exists(o.out, ec) && !(fs::is_directory(o.out, ec) && fs::is_empty(o.out, ec)))
    return userError("--out " + o.out + " already exists and is not empty; choose another output directory");

  // Every option before any file is read: a mistake is named even when the path is missing too.
  scene::SceneOptions so;
  if (Status s = applyStreamingAndTreeOptions(o.streaming, scene::StreamingMode::Settled, o.treeCli, so); !s)
    return reportError(log, s.error());
  auto path = flight::loadFlightPath(o.path);
  if (!path) return reportError(log, path.error());
  if (Status s = flight::checkRecordable(path->duration(), o.fps, o.warmupS, o.path); !s)
    return reportError(log, s.error());
  o.simulation = resolveSimulationOptions(o.simulationCli, &*path);
  auto dataset = resolveDataset(o.dataset, o.samplesDir, log);
  if (!dataset) return reportError(log, dataset.error());
  if (!streaming::isHttpLocation(*dataset)) {  // a local dataset is checked against the path before the GPU is touched
    auto meta = datasets::readDatasetMeta(*dataset);
    if (!meta) return reportError(log, meta.error());
    if (Status s = flight::checkInside(*path, meta->bounds); !s) return userError(o.path + ": " + s.error().message);
  }

  so.dataset = *dataset;
  so.simulation = o.simulation;
  applySunOptions(*sun, &*path, so);
  applyRendererOptions({width, height, o.msaa, o.device, o.validate}, log, so);
  auto scene = scene::Scene::open(so);
  if (!scene) return reportError(log, scene.error());
  if (Status s = flight::checkInside(*path, (*scene)->info().bounds); !s)
    return userError(o.path + ": " + s.error().message);
  logSceneOpened(**scene, log);

  scene::RecordingRequest request;
  request.out = o.out;
  request.playback.fps = o.fps;
  request.playback.warmupS = o.warmupS;
  request.playback.framesEvery = o.framesEvery;
  request.playback.aovs = *aovs;
  request.playback.framesInFlight = static_cast<std::size_t>(o.framesInFlight);
  request.plots = !o.noPlots;
  request.pathFile = o.path;
  request.speciesCatalog = o.streaming.species.empty() ? "default" : o.streaming.species;
  return recordAndReport(**scene, *path, request, log);
}

}  // namespace vegstream::app
