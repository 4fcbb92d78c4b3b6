// The streaming, terrain and plant options shared by fly, record and snapshot (streaming_cli.h):
// registered on a command, checked, and applied to the scene's options.
#include "app/streaming_cli.h"

#include <cmath>

#include <CLI/CLI.hpp>

#include "core/number_text.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/species_catalog.h"

namespace vegstream::app {
namespace {

Error bad(const std::string& m) { return makeError(ErrorKind::InvalidInput, m); }
uint64_t bytes(double mb) { return static_cast<uint64_t>(std::llround(mb * 1024.0 * 1024.0)); }

// The memory budgets, --streaming and the terrain's options.
void addTerrainOptions(CLI::App& cmd, StreamingCli& o, bool withMode) {
  cmd.add_option("--cpu-budget-mb", o.cpuBudgetMb, "Memory for decoded tiles, MiB (never exceeded)")
      ->capture_default_str();
  cmd.add_option("--gpu-budget-mb", o.gpuBudgetMb, "GPU memory for imagery tiles, MiB (never exceeded)")
      ->capture_default_str();
  cmd.add_option("--upload-mb-per-frame", o.uploadMbPerFrame, "Imagery uploaded to the GPU per frame at most, MiB")
      ->capture_default_str();
  if (withMode)
    cmd.add_option("--streaming", o.mode,
                   "settled: each frame waits for the tiles it wants (the wait is its own column); "
                   "realtime: I/O races the frames as in interactive flight")
        ->check(CLI::IsMember({"settled", "realtime"}))
        ->default_str("settled");
  cmd.add_flag("--no-look-ahead", o.noLookAhead, "Do not prefetch the tiles of the next seconds of the flight");
  cmd.add_option("--terrain-error-px", o.terrainErrorPx, "Screen-space error bound of the terrain, pixels")
      ->capture_default_str();
  cmd.add_option("--terrain-max-nodes", o.terrainMaxNodes, "Most terrain tiles drawn per frame")->capture_default_str();
  cmd.add_option("--terrain-max-triangles", o.terrainMaxTriangles, "Triangle budget of the ROAM terrain mesh")
      ->capture_default_str();
  cmd.add_option("--canopy-m", o.canopyM,
                 "Tallest plant, metres: terrain culling keeps triangles whose plants can be seen")
      ->capture_default_str();
  cmd.add_option("--terrain-detail", o.terrainDetail,
                 "Strength of the close-up terrain detail textures, 0 (the bare imagery) … 1")
      ->capture_default_str();
  cmd.add_option("--terrain-shading", o.terrainShading,
                 "deferred: a visibility pass, then every pixel shaded in compute (fast where graphics units are "
                 "few); compute: rasterised in compute too (no graphics work for the terrain); forward: fragments "
                 "shaded as drawn; auto: compute on a GPU, deferred on a CPU rasteriser (lavapipe), else forward")
      ->check(CLI::IsMember({"auto", "forward", "deferred", "compute"}))
      ->capture_default_str();
  cmd.add_option("--terrain-geometry", o.terrainGeometry,
                 "resident: the terrain's vertices stay on the GPU, ROAM's chunks uploaded only when new or moved; "
                 "copied: every frame copies them all (the same images, for comparison)")
      ->check(CLI::IsMember({"resident", "copied"}))
      ->capture_default_str();
  cmd.add_option("--terrain-depth-tiles", o.terrainDepthTiles,
                 "With --terrain-shading compute: vegetation: the terrain's depth goes into the depth attachment "
                 "only where plants or trees may be drawn; all: everywhere (the same images, for comparison); "
                 "checked: as vegetation, the tiles left out at the near plane, so that anything drawn there "
                 "vanishes (a test of the marks)")
      ->check(CLI::IsMember({"vegetation", "all", "checked"}))
      ->capture_default_str();
  cmd.add_option("--frame-workers", o.frameWorkers,
                 "Most worker threads the frame's own parallel loops (terrain tessellation and copies) use beside "
                 "the frame thread; 0: all of them (one per core)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd.add_option("--seed-horizon-m", o.seedHorizonM,
                 "Seed triangles (plants) only within this distance, metres (each species also stops at its "
                 "catalog horizon_m)")
      ->capture_default_str();
}

// Fetching over HTTP.
void addHttpOptions(CLI::App& cmd, StreamingCli& o) {
  cmd.add_option("--http-cache", o.httpCache,
                 "Directory of an on-disk cache for tiles fetched over HTTP (only tiles that decode as the "
                 "dataset's are kept)");
  cmd.add_flag("--allow-redirects", o.allowRedirects,
               "Follow HTTP redirects to other hosts too (without it, only to the dataset URL's own host; "
               "never to anything but http:// or https://)");
  cmd.add_option("--http-timeout-s", o.httpTimeoutS,
                 "Give up a file fetched over HTTP after this many seconds, all its retries included (it is then "
                 "drawn from its parent tile); an attempt that stalls is retried after 5 s")
      ->capture_default_str();
}

// Seeding and drawing the plants.
void addPlantOptions(CLI::App& cmd, StreamingCli& o) {
  cmd.add_option("--plant-density", o.plantDensity,
                 "Plants per pixel² of a seed triangle's projected area (ρ of eq. 1), pixels of a 1080-line view "
                 "whatever the window: the level of detail that thins plants with distance; near the camera "
                 "the catalog's density_m2 decides")
      ->capture_default_str();
  cmd.add_option("--plant-max", o.plantMax, "Most plants per seed triangle (n_max of eq. 1): a ceiling")
      ->capture_default_str();
  cmd.add_option("--plant-contour", o.plantContour,
                 "α of Belyaev's contour term: more plants where the ground is seen edge-on (8 in the paper; "
                 "0: off, eq. 1 alone)")
      ->capture_default_str();
  cmd.add_option("--cluster-size", o.clusterSize, "Plants per cluster that share one species lookup (C)")
      ->capture_default_str();
  cmd.add_option("--species", o.species, "Species catalog (JSON, see config/species.json); default: the built-in one");
  cmd.add_flag("--no-plants", o.noPlants, "Draw the terrain only: no seeding, no classify pass");
  cmd.add_option("--plant-style", o.plantStyle,
                 "plants: the species pipelines (grass, gravel, flowers; trees are drawn by the tree pass, --trees); markers: one marker "
                 "per plant, the classification alone; hidden: classified and counted, not drawn; coverage: as "
                 "plants, in flat magenta without shadows, to measure what they cover")
      ->capture_default_str();
  cmd.add_option("--plant-segments", o.plantSegments, "Segments of a blade at full detail (n_max of eq. 4)")
      ->capture_default_str();
  cmd.add_option("--plant-lod-m", o.plantLodM,
                 "Blades have full detail within this distance, n_max / d² beyond, metres")
      ->capture_default_str();
  cmd.add_flag("--no-plant-shadows", o.noPlantShadows, "No planar shadows under the plants");
  cmd.add_option("--plant-fades", o.plantFades,
                 "on: plants grow in and shrink away (level of detail, horizons, imagery changes); off: they "
                 "appear and vanish at full size, for comparison")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd.add_option("--plant-shadow-m", o.plantShadowM,
                 "Planar shadows are drawn within this distance, fading out over its last quarter, metres")
      ->capture_default_str();
  cmd.add_option("--occlusion-culling", o.occlusionCulling,
                 "on: seed triangles hidden behind the terrain (Hi-Z of its depth) are neither classified nor "
                 "drawn; off: all are, for comparison")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd.add_option("--blade-path", o.bladePath,
                 "How plants become triangles: auto (the fastest the device offers: compute), tessellation "
                 "(tessellation + geometry shaders), compute (expanded once per plant in compute), mesh (not in "
                 "this build)")
      ->check(CLI::IsMember({"auto", "tessellation", "compute", "mesh"}))
      ->capture_default_str();
}

// Every number and word in range, in the order of the options.
Status checkStreamingOptions(const StreamingCli& o) {
  if (!(o.cpuBudgetMb >= 1.0 && o.cpuBudgetMb <= 1e6))
    return bad("--cpu-budget-mb " + std::to_string(o.cpuBudgetMb) + ": must be 1 … 1000000 MiB");
  if (!(o.gpuBudgetMb >= 0.25 && o.gpuBudgetMb <= 1e6))
    return bad("--gpu-budget-mb " + std::to_string(o.gpuBudgetMb) +
               ": must be 0.25 … 1000000 MiB (one imagery tile is 0.25)");
  if (!(o.uploadMbPerFrame >= 0.25 && o.uploadMbPerFrame <= 1e5))
    return bad("--upload-mb-per-frame " + std::to_string(o.uploadMbPerFrame) + ": must be 0.25 … 100000 MiB");
  if (!(o.terrainErrorPx >= 0.1 && o.terrainErrorPx <= 1000.0))
    return bad("--terrain-error-px " + std::to_string(o.terrainErrorPx) + ": must be 0.1 … 1000 pixels");
  if (o.terrainMaxNodes < 1 || o.terrainMaxNodes > 100000)
    return bad("--terrain-max-nodes " + std::to_string(o.terrainMaxNodes) + ": must be 1 … 100000");
  if (o.terrainMaxTriangles < 2 || o.terrainMaxTriangles > 10'000'000)
    return bad("--terrain-max-triangles " + std::to_string(o.terrainMaxTriangles) + ": must be 2 … 10000000");
  if (!(o.terrainDetail >= 0.0 && o.terrainDetail <= 1.0))
    return bad("--terrain-detail " + std::to_string(o.terrainDetail) + ": must be 0 … 1");
  if (!(o.canopyM >= 0.0 && o.canopyM <= 200.0))
    return bad("--canopy-m " + std::to_string(o.canopyM) + ": must be 0 … 200 metres");
  if (!(o.seedHorizonM >= 0.0 && o.seedHorizonM <= 20000.0))
    return bad("--seed-horizon-m " + std::to_string(o.seedHorizonM) + ": must be 0 … 20000 metres");
  if (!(o.plantDensity >= 0.0 && o.plantDensity <= 100.0))
    return bad("--plant-density " + std::to_string(o.plantDensity) + ": must be 0 … 100 plants per pixel²");
  if (!(o.plantContour >= 0.0 && o.plantContour <= 64.0))
    return bad("--plant-contour " + numberText(o.plantContour) + ": must be 0 (off) … 64");
  if (!(o.plantMax >= 0.0 && o.plantMax <= 65536.0))
    return bad("--plant-max " + std::to_string(o.plantMax) + ": must be 0 … 65536 plants per seed triangle");
  if (o.clusterSize < 1 || o.clusterSize > static_cast<int>(vegetation::kMaxClusterSize))
    return bad("--cluster-size " + std::to_string(o.clusterSize) + ": must be 1 … " +
               std::to_string(vegetation::kMaxClusterSize));
  if (o.plantStyle != "plants" && o.plantStyle != "markers" && o.plantStyle != "hidden" && o.plantStyle != "coverage")
    return bad("--plant-style " + o.plantStyle + ": must be plants, markers, hidden or coverage");
  if (o.occlusionCulling != "on" && o.occlusionCulling != "off")
    return bad("--occlusion-culling " + o.occlusionCulling + ": must be on or off");
  if (o.plantSegments < 1 || o.plantSegments > 16)
    return bad("--plant-segments " + std::to_string(o.plantSegments) + ": must be 1 … 16");
  if (!(o.plantLodM > 0.0 && o.plantLodM <= 1000.0))
    return bad("--plant-lod-m " + std::to_string(o.plantLodM) + ": must be more than 0 and at most 1000 metres");
  if (!(o.plantShadowM > 0.0 && o.plantShadowM <= 10000.0))
    return bad("--plant-shadow-m " + std::to_string(o.plantShadowM) +
               ": must be more than 0 and at most 10000 metres");
  if (!(o.httpTimeoutS >= 1.0 && o.httpTimeoutS <= 3600.0))
    return bad("--http-timeout-s " + numberText(o.httpTimeoutS) + ": must be 1 … 3600 seconds");
  return {};
}

// The budgets, the streaming mode and the terrain's options into scene.
void applyTerrainOptions(const StreamingCli& o, scene::StreamingMode defaultMode, scene::SceneOptions& scene) {
  scene.streaming.cpuBudgetBytes = bytes(o.cpuBudgetMb);
  scene.streaming.gpuBudgetBytes = bytes(o.gpuBudgetMb);
  scene.streaming.uploadBytesPerFrame = bytes(o.uploadMbPerFrame);
  scene.mode = o.mode.empty() ? defaultMode
                              : (o.mode == "settled" ? scene::StreamingMode::Settled : scene::StreamingMode::Realtime);
  scene.lookAhead = !o.noLookAhead;
  scene.terrain.maxErrorPx = o.terrainErrorPx;
  scene.terrain.maxNodes = o.terrainMaxNodes;
  scene.terrain.roam.maxTriangles = static_cast<uint64_t>(o.terrainMaxTriangles);
  scene.terrain.roam.canopyM = o.canopyM;
  scene.terrainDetail = static_cast<float>(o.terrainDetail);
  scene.renderer.terrainShading = o.terrainShading == "forward"    ? render::TerrainShading::Forward
                                  : o.terrainShading == "deferred" ? render::TerrainShading::Deferred
                                  : o.terrainShading == "compute"  ? render::TerrainShading::Compute
                                                                   : render::TerrainShading::Auto;
  scene.renderer.residentTerrain = o.terrainGeometry == "resident";
  scene.renderer.depthTiles = *render::parseDepthTiles(o.terrainDepthTiles);  // checked by the option
  scene.frameWorkers = o.frameWorkers;
  scene.terrain.seeds.horizonM = o.seedHorizonM;
  scene.terrain.seeds.density = o.plantDensity;
  scene.terrain.seeds.maxPlants = o.plantMax;
  scene.terrain.seeds.contourAlpha = o.plantContour;
}

// The plants' options into scene; the blade path must be one this build knows.
Status applyPlantOptions(const StreamingCli& o, scene::SceneOptions& scene) {
  scene.clusterSize = static_cast<uint32_t>(o.clusterSize);
  scene.plants = !o.noPlants;
  scene.plantStyle = o.plantStyle == "markers"  ? render::PlantStyle::Markers
                     : o.plantStyle == "hidden" ? render::PlantStyle::Hidden
                                                : render::PlantStyle::Plants;
  scene.plantDraw.maxSegments = static_cast<uint32_t>(o.plantSegments);
  scene.plantDraw.lodDistanceM = static_cast<float>(o.plantLodM);
  scene.plantDraw.flatColour = o.plantStyle == "coverage";
  scene.plantDraw.fades = o.plantFades != "off";
  scene.plantDraw.shadows = !o.noPlantShadows && !scene.plantDraw.flatColour;
  scene.plantDraw.shadowDistanceM = static_cast<float>(o.plantShadowM);
  scene.occlusionCulling = o.occlusionCulling == "on";
  // Checked against the device when the renderer is made (mesh: refused there, naming the device).
  const auto bladePath = render::parseBladePath(o.bladePath);
  if (!bladePath) return bad("--blade-path " + o.bladePath + ": must be auto, tessellation, compute or mesh");
  scene.renderer.bladePath = *bladePath;
  return {};
}

}  // namespace

void addStreamingOptions(CLI::App& cmd, StreamingCli& o, bool withMode) {
  addTerrainOptions(cmd, o, withMode);
  addHttpOptions(cmd, o);
  addPlantOptions(cmd, o);
}

Status applyStreamingOptions(const StreamingCli& o, scene::StreamingMode defaultMode, scene::SceneOptions& scene) {
  if (Status s = checkStreamingOptions(o); !s) return s;
  if (!o.species.empty()) {
    auto catalog = vegetation::loadSpeciesCatalog(o.species);
    if (!catalog) return catalog.error();
    scene.species = std::make_shared<const vegetation::SpeciesCatalog>(std::move(*catalog));
  }
  applyTerrainOptions(o, defaultMode, scene);
  if (Status s = applyPlantOptions(o, scene); !s) return s;
  if (!o.httpCache.empty()) scene.httpCacheDir = o.httpCache;
  scene.httpAllowRedirects = o.allowRedirects;
  scene.httpRequestDeadlineMs = std::lround(o.httpTimeoutS * 1000.0);
  return {};
}

}  // namespace vegstream::app
