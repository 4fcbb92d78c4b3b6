// `vegstream snapshot` (snapshot_command.h).

#include "app/snapshot_command.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "app/record_command.h"
#include "app/scene_setup.h"
#include "app/settled_still.h"
#include "core/number_text.h"
#include "datasets/dataset_format.h"
#include "scene/frame_aovs.h"
#include "scene/frame_sidecar.h"
#include "streaming/open_tile_source.h"

namespace vegstream::app {
namespace fs = std::filesystem;

namespace {

constexpr double kMaxSimulationTimeS = 600.0;

constexpr double kMinClearanceM = 0.5;  // the camera at least this far above the ground
constexpr double kMaxAltM = 100000.0;
constexpr double kMaxPitchDeg = 89.0;  // ±90 looks along the up axis: no heading, no view

Error userError(const std::string& message) { return makeError(ErrorKind::InvalidInput, message); }

// --out: a .png file in an existing directory (it may exist: it is replaced when the new one is complete).
Status checkOut(const std::string& out) {
  const fs::path p = out;
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  std::error_code ec;
  if (fs::is_directory(p, ec)) return userError("--out " + out + " is a directory; give a file name ending in .png");
  if (ext != ".png")
    return userError("--out " + out + ": the still is written as PNG; give a file name ending in .png");
  if (fs::is_directory(scene::sidecarPathFor(p), ec))
    return userError("--out " + out + ": its sidecar " + scene::sidecarPathFor(p).string() + " is a directory");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec)) return userError("--out " + out + ": directory " + dir.string() + " does not exist");
  return {};
}

// The pose's numbers on their own: finite, pitch in range, altitude plausible.
Status checkPoseNumbers(const SnapshotOptions& o) {
  if (!std::isfinite(o.latDeg) || o.latDeg < -90.0 || o.latDeg > 90.0)
    return userError("--lat " + numberText(o.latDeg) + ": must be -90 … 90 degrees");
  if (!std::isfinite(o.lonDeg) || o.lonDeg < -180.0 || o.lonDeg > 180.0)
    return userError("--lon " + numberText(o.lonDeg) + ": must be -180 … 180 degrees");
  if (!std::isfinite(o.headingDeg))
    return userError("--heading " + numberText(o.headingDeg) + ": must be a number of degrees");
  if (!std::isfinite(o.pitchDeg) || std::abs(o.pitchDeg) > kMaxPitchDeg)
    return userError("--pitch " + numberText(o.pitchDeg) + ": must be -89 … 89 degrees (0 level, negative looks down)");
  if (!std::isfinite(o.altM) || o.altM > kMaxAltM)
    return userError("--alt " + numberText(o.altM) + ": must be a number of metres up to 100000");
  if (o.altRef == "ground" && o.altM < kMinClearanceM)
    return userError("--alt " + numberText(o.altM) + ": the camera must be at least 0.5 m above the ground");
  return {};
}

// The pose against the dataset's coverage, naming the option that is outside it.
Status checkCoverage(const SnapshotOptions& o, const geo::GeoBounds& b, const std::string& dataset) {
  const bool latOut = o.latDeg < b.southDeg || o.latDeg > b.northDeg;
  const bool lonOut = o.lonDeg < b.westDeg || o.lonDeg > b.eastDeg;
  if (!latOut && !lonOut) return {};
  const std::string which = latOut && lonOut ? "--lat " + numberText(o.latDeg) + " --lon " + numberText(o.lonDeg)
                            : latOut         ? "--lat " + numberText(o.latDeg)
                                             : "--lon " + numberText(o.lonDeg);
  char cover[160];
  std::snprintf(cover, sizeof(cover), "lat %.5f … %.5f, lon %.5f … %.5f", b.southDeg, b.northDeg, b.westDeg, b.eastDeg);
  return userError(which + ": outside dataset " + dataset + ", which covers " + cover);
}

// The AOVs first, then the PNG and its sidecar; the AOVs are removed again when those fail.
Status writeStill(const fs::path& png, const SettledStill& still, const std::string& sidecar,
                  const scene::AovSelection& aovs) {
  if (aovs.any()) {
    if (!still.aov) return makeError(ErrorKind::Internal, "the still has no AOVs");
    if (Status s = scene::writeFrameAovs(png, *still.aov, aovs); !s) return s;
  }
  Status s = scene::writeFrameWithSidecar(png, still.image, sidecar);
  if (!s && aovs.any()) {
    std::error_code ec;
    if (aovs.depth) fs::remove(scene::aovPathFor(png, "depth"), ec);
    if (aovs.coverage) fs::remove(scene::aovPathFor(png, "coverage"), ec);
    if (aovs.species) fs::remove(scene::aovPathFor(png, "species"), ec);
  }
  return s;
}

}  // namespace

CLI::App* addSnapshotCommand(CLI::App& cli, SnapshotOptions& o) {
  auto* cmd = cli.add_subcommand("snapshot", "Render one still frame from a pose to a PNG, once streaming has settled");
  cmd->add_option("dataset", o.dataset,
                  "Dataset directory (vegstream import) or http(s):// URL of one; default: the Zion sample");
  cmd->add_option("--lat", o.latDeg, "Camera latitude, degrees (WGS 84)")->required();
  cmd->add_option("--lon", o.lonDeg, "Camera longitude, degrees (WGS 84)")->required();
  cmd->add_option("--alt", o.altM, "Camera altitude, metres above the ground (or sea level with --alt-ref msl)")
      ->required();
  cmd->add_option("--alt-ref", o.altRef, "What --alt is measured from: ground or msl")
      ->check(CLI::IsMember({"ground", "msl"}))
      ->capture_default_str();
  cmd->add_option("--heading", o.headingDeg, "View direction, degrees clockwise from north")->required();
  cmd->add_option("--pitch", o.pitchDeg, "View pitch, degrees: 0 level, negative looks down (-89 … 89)")->required();
  cmd->add_option("--out", o.out, "PNG file to write (replaced when the new one is complete)")->required();
  cmd->add_option("--size", o.size, "Image size WxH")->capture_default_str();
  cmd->add_option("--msaa", o.msaa, "Samples per pixel (1, 2, 4, 8, 16 where the device offers them)")
      ->capture_default_str();
  cmd->add_option("--device", o.device, "Use the GPU whose name contains NAME (see `vegstream devices`)");
  cmd->add_flag("--validate", o.validate, "Turn on the Vulkan validation layers");
  addSceneOptions(*cmd, o.streaming, false, o.simulationCli, o.treeCli, o.sunCli);
  cmd->add_option("--time", o.timeS,
                  "Show the wind as it is S seconds into a flight held at this pose since 0 (0 … 600)")
      ->capture_default_str();
  cmd->add_option("--aov", o.aov,
                  "Also write measurement AOVs beside the PNG as 32-bit float TIFFs, comma-separated: depth "
                  "(F.depth.tif, metres; 0 sky), coverage (F.coverage.tif, 0 … 1 plants and trees), species "
                  "(F.species.tif, catalog index + 1; 0 none)");
  return cmd;
}

namespace {

// --size, --msaa, the pose's numbers and the simulation's options (resolved into o.simulation).
Status checkSnapshotOptions(SnapshotOptions& o, uint32_t& width, uint32_t& height) {
  if (!parseFrameSize(o.size, width, height))
    return userError("--size " + o.size + ": expected WxH with each side 1 … 16384, e.g. 1280x720");
  if (o.msaa != 1 && o.msaa != 2 && o.msaa != 4 && o.msaa != 8 && o.msaa != 16)
    return userError("--msaa " + std::to_string(o.msaa) + ": samples per pixel must be 1, 2, 4, 8 or 16");
  if (Status s = checkPoseNumbers(o); !s) return s;
  if (Status s = checkSimulationOptions(o.simulationCli); !s) return s;
  o.simulation = resolveSimulationOptions(o.simulationCli, nullptr);
  return {};
}

// The camera at the pose, once the scene covers it and the ground under it is known.
Result<flight::FlightSample> snapshotPose(const SnapshotOptions& o, scene::Scene& scene, const std::string& dataset) {
  if (Status s = checkCoverage(o, scene.info().bounds, dataset); !s) return s.error();
  const double ground = scene.groundHeight(o.latDeg, o.lonDeg);
  if (std::isnan(ground))
    return userError("--lat " + numberText(o.latDeg) + " --lon " + numberText(o.lonDeg) + ": dataset " + dataset +
                     " has no elevation data there");
  const double heightMsl = o.altRef == "msl" ? o.altM : ground + o.altM;
  if (heightMsl - ground < kMinClearanceM)
    return userError("--alt " + numberText(o.altM) +
                     " (above sea level): the camera must be at least 0.5 m "
                     "above the ground, which is at " +
                     numberText(ground) + " m there");
  flight::FlightSample pose;
  pose.position = {o.latDeg, o.lonDeg, heightMsl};
  pose.headingDeg = std::fmod(std::fmod(o.headingDeg, 360.0) + 360.0, 360.0);
  pose.pitchDeg = o.pitchDeg;
  pose.heightAboveGroundM = heightMsl - ground;
  return pose;
}

// The run's summary: what was drawn, how long it took to settle, and the sun.
void logSnapshot(const SnapshotOptions& o, const SettledStill& still, const scene::Scene& scene, bool plantsOn,
                 uint32_t width, uint32_t height, const flight::FlightSample& pose, const Logger& log) {
  const std::string plants = !plantsOn             ? "no plants"
                             : still.plantsCounted ? std::to_string(still.plants) + " plants drawn"
                                                   : "plants not counted on this device";
  const std::string frames = still.settled ? std::to_string(still.frames) + " frames to settle"
                                           : "not settled after " + std::to_string(still.frames) + " frames";
  log->info("snapshot written to {}: {}x{}, {:.1f} m above the ground, {} terrain triangles, {} ({})", o.out, width,
            height, pose.heightAboveGroundM, still.terrainTriangles, plants, frames);
  const geo::SolarPosition& sunAt = still.record.sun;
  log->info("sidecar {}: sun at {} ({} date-time), azimuth {:.2f}°, elevation {:.2f}°",
            scene::sidecarPathFor(o.out).string(), geo::formatIsoDateTime(still.record.datetime),
            scene::toString(scene.sunClock().source), sunAt.azimuthDeg, sunAt.elevationDeg);
}

}  // namespace

int runSnapshot(SnapshotOptions o, const Logger& log) {
  uint32_t width = 0, height = 0;
  if (Status s = checkSnapshotOptions(o, width, height); !s) return reportError(log, s.error());
  auto sun = checkSunOptions(o.sunCli);
  if (!sun) return reportError(log, sun.error());
  if (!std::isfinite(o.timeS) || o.timeS < 0.0 || o.timeS > kMaxSimulationTimeS)
    return reportError(log, userError("--time " + numberText(o.timeS) + ": must be 0 … 600 seconds"));
  if (Status s = checkOut(o.out); !s) return reportError(log, s.error());
  auto aovs = scene::parseAovList(o.aov);
  if (!aovs) return reportError(log, aovs.error());

  scene::SceneOptions so;
  if (Status s = applyStreamingAndTreeOptions(o.streaming, scene::StreamingMode::Settled, o.treeCli, so); !s)
    return reportError(log, s.error());
  so.mode = scene::StreamingMode::Settled;  // a still shows the finest tiles its view wants
  auto dataset = resolveDataset(o.dataset, o.samplesDir, log);
  if (!dataset) return reportError(log, dataset.error());
  if (!streaming::isHttpLocation(*dataset)) {  // a local dataset is checked against the pose before the GPU is touched
    auto meta = datasets::readDatasetMeta(*dataset);
    if (!meta) return reportError(log, meta.error());
    if (Status s = checkCoverage(o, meta->bounds, *dataset); !s) return reportError(log, s.error());
  }

  so.dataset = *dataset;
  so.simulation = o.simulation;
  applySunOptions(*sun, nullptr, so);
  applyRendererOptions({width, height, o.msaa, o.device, o.validate}, log, so);
  auto opened = scene::Scene::open(so);
  if (!opened) return reportError(log, opened.error());
  scene::Scene& scene = **opened;
  auto pose = snapshotPose(o, scene, *dataset);
  if (!pose) return reportError(log, pose.error());
  logSceneOpened(scene, log);
  auto still = renderSettledStill(scene, *pose, log, 40, o.timeS, aovs->any());
  if (!still) return reportError(log, still.error());
  if (!still->settled)
    log->warn("the view did not settle in {} frames (the last one still had {}); writing the last frame", still->frames,
              still->unsettled);
  if (still->fallbackPieces > 0)
    log->warn(
        "{} terrain pieces are drawn from coarser tiles: the tiles the view wants do not fit "
        "--cpu-budget-mb / --gpu-budget-mb",
        still->fallbackPieces);
  const std::string sidecar = scene::frameSidecarJson(still->record, width, height, scene);
  if (Status s = writeStill(o.out, *still, sidecar, *aovs); !s) return reportError(log, s.error());

  const render::ValidationLog* validation = scene.renderer().validationLog();
  const int validationErrors = validation ? validation->errors() : 0;
  if (validationErrors > 0) log->error("validation reported {} errors", validationErrors);
  logSnapshot(o, *still, scene, so.plants, width, height, *pose, log);
  return validationErrors > 0 ? kExitFailure : kExitOk;
}

}  // namespace vegstream::app
