#pragma once
// What callers hand the renderer each frame and what they get back: plain data only, so
// folders above render/ never see a Vulkan type.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "geo/camera.h"
#include "render/classify_layout.h"
#include "render/gpu_timing.h"
#include "render/overlay_types.h"
#include "render/tree_layout.h"
#include "terrain/terrain_mesh.h"
#include "vegetation/canopy_cells.h"

namespace vegstream::simulation {
struct GpuStep;
}

namespace vegstream::render {

// The camera (local ENU, double precision) and its matrices are geo's (geo/camera.h): the scene
// makes it once per frame and the terrain's views share it.
using geo::Camera;
using geo::projection;
using geo::reverseZDepth;
using geo::viewRotation;

// The light of a frame: the sun's direction (its colour, the sky and the air come from the
// atmosphere model for it, render/atmosphere_pass.h) and the exposure.
struct Lighting {
  glm::dvec3 sunDirection{-0.85, -0.15, 0.5};  // towards the sun (late afternoon, west), local ENU; normalised on use
  // Exposure (EV100): fixed when set (`--exposure EV`); otherwise automatic from the frame's
  // luminance histogram, a function of the frame alone unless `adaptExposure` (the window)
  // smooths it over time.
  std::optional<float> exposureEv;
  bool adaptExposure = false;
  float adaptSeconds = 0.0f;  // with adaptExposure: the time since the last frame
};

// Imagery tiles live in one GPU texture array, one 256 × 256 sRGB layer per tile; the streamer
// (streaming/) decides which tile has which layer.
inline constexpr uint32_t kImageryTileSize = 256;

// One piece of terrain to draw this frame: a mesh (float vertices relative to its double
// origin) coloured by an imagery layer, possibly fading in over a coarser one.
struct TerrainDraw {
  const terrain::TerrainMesh* mesh = nullptr;
  int32_t imageryLayer = -1;                    // −1: coloured by height and slope
  glm::vec4 imageryUv{1.0f, 1.0f, 0.0f, 0.0f};  // layer uv = vertex uv · xy + zw
  int32_t previousLayer = -1;                   // the layer it fades from (−1: none)
  glm::vec4 previousUv{1.0f, 1.0f, 0.0f, 0.0f};
  float imageryBlend = 1.0f;  // 0: only previousLayer … 1: only imageryLayer
};

// Copies a tile into an imagery layer before the frame draws. `rgba` (256 × 256 × 4 bytes)
// must stay alive until submitFrame returns. The copy waits for every earlier command on the
// queue, so a frame still in flight that draws the layer's old tile finishes first (the
// streamer also delays slot reuse). The upload copies only what it checked: an `rgba` of any
// other size (or an `ndvi` neither empty nor 256 × 256) is skipped, never over-read — the
// streamer's decoders already refuse such tiles (datasets/tile_codec.h), this is the last guard.
struct ImageryUpload {
  uint32_t layer = 0;
  std::span<const uint8_t> rgba;
  // 256 × 256 NDVI bytes (datasets/tile_codec.h) for the layer, or empty: none there. Used only
  // when the imagery array was sized with NDVI (Renderer::setImageryLayers).
  std::span<const uint8_t> ndvi;
  // 256 × 256 landcover class codes (datasets/landcover.h; 0 = no class) for the layer, or empty:
  // none there. Used only when the imagery array was sized with landcover.
  std::span<const uint8_t> landcover;
};

// The layers that travel with each imagery layer (Renderer::setImageryLayers): in one RG8 array
// beside the imagery, R the NDVI byte, G the landcover class code (0 in both: none).
struct ImageryCompanions {
  bool ndvi = false;
  bool landcover = false;
  bool any() const { return ndvi || landcover; }
  // The classify pass's push constant (classify.comp): bit 0 NDVI, bit 1 landcover.
  uint32_t flags() const { return (ndvi ? 1u : 0u) | (landcover ? 2u : 0u); }
};

// What the classify pass did in one frame (render/classify_pass.h): the CPU's bin layout and the
// GPU's counts per species (read back after the frame's fence).
inline constexpr size_t kSpeciesSlots = 16;  // = vegetation::kMaxSpecies
struct VegetationFigures {
  uint32_t seedTriangles = 0;  // submitted to the classify pass
  uint32_t bins = 0;           // non-empty bins (one dispatch each)
  uint64_t clusters = 0;       // species lookups: seeds of cluster 0 + further clusters, before rejection
  uint64_t clusterSlots = 0;   // threads the bins' dispatches covered (≥ clusters)
  bool gpuCounts = false;      // the per-species counts below were read back
  std::array<uint32_t, kSpeciesSlots> groups{};  // groups appended per species (drawn: ≤ capacity)
  std::array<uint32_t, kSpeciesSlots> plants{};  // plants in those groups
  uint64_t groupsTotal = 0, plantsTotal = 0;
  // Groups each species wanted before the overflow thinning (vegetation/overflow_thinning.h),
  // and the pressure this frame thinned them with.
  std::array<uint32_t, kSpeciesSlots> wanted{};
  std::array<float, kSpeciesSlots> thinning{};
  bool overflow = false;  // a species' buffer was full: some groups were not drawn
  // Hi-Z occlusion culling (render/hiz_pass.h), read back with the counts; zero when it was off.
  bool occlusionCulling = false;   // asked for this frame (the counts are 0 when there was nothing to test)
  uint64_t cullTested = 0;          // seed triangles with plants that were tested
  uint64_t cullCulled = 0;          // of them, hidden for every species: never expanded
  uint64_t cullClustersCulled = 0;  // their species lookups (classify work items) skipped
  uint64_t cullPlantsCulled = 0;    // Σ ceil(N) of the culled triangles: plants never made
  // Groups classified but dropped because their species' plants are hidden on their triangle
  // (a ridge hides grass, not the trees of the same triangle), and the plants in them.
  uint64_t cullGroupsCulled = 0, cullGroupPlantsCulled = 0;
  // The compute blade path (render/blade_pass.h), when it drew the frame: the triangles and
  // vertices it wrote for the plant kinds (shadows included), and the plants that did not fit
  // its buffers (not drawn; 0 unless the scene outgrew the buffers' ceiling).
  bool bladeCounts = false;
  uint64_t bladeTriangles = 0, bladeVertices = 0;
  uint32_t bladesDropped = 0;
};

// Plants to classify and draw this frame (render/classify_pass.h): the seed triangles, camera-
// relative, and the cluster size C. Must stay alive until submitFrame returns.
enum class PlantStyle {
  Plants,   // the species pipelines (grass, gravel, flowers); markers for kinds without one (trees)
  Markers,  // one marker per plant for every species: the classification alone
  Hidden,   // classified and counted, not drawn
};

// How the plant kinds (grass, gravel, flowers) become triangles (render/README.md "Blade paths").
enum class BladePath {
  Auto,          // the fastest the device offers: Compute (every Vulkan device has compute)
  Tessellation,  // vertex → tessellation → per-kind geometry shader (render/plant_pass.h)
  Compute,       // a compute pass expands each plant once; a trivial vertex shader draws it (render/blade_pass.h)
  Mesh,          // VK_EXT_mesh_shader: not implemented in this build (Renderer::create refuses it)
};

inline const char* bladePathName(BladePath p) {
  switch (p) {
    case BladePath::Auto: return "auto";
    case BladePath::Tessellation: return "tessellation";
    case BladePath::Compute: return "compute";
    case BladePath::Mesh: return "mesh";
  }
  return "auto";
}

inline std::optional<BladePath> parseBladePath(std::string_view s) {
  for (BladePath p : {BladePath::Auto, BladePath::Tessellation, BladePath::Compute, BladePath::Mesh})
    if (s == bladePathName(p)) return p;
  return std::nullopt;
}

// With the terrain rasterised in compute: where its depth goes into the depth attachment
// (render/terrain_depth_handover.h, `--terrain-depth-tiles`).
enum class DepthTiles {
  Vegetation,  // the tiles a plant or a tree may be drawn over
  All,         // every tile (the way before; for comparison)
  // As Vegetation, the tiles left out first cleared to the near plane, so that any plant or tree
  // drawn over one vanishes: a test that the marks hold everything drawn.
  Checked,
};

inline std::optional<DepthTiles> parseDepthTiles(std::string_view s) {
  if (s == "vegetation") return DepthTiles::Vegetation;
  if (s == "all") return DepthTiles::All;
  if (s == "checked") return DepthTiles::Checked;
  return std::nullopt;
}

// How the species pipelines draw (render/plant_pass.h).
struct PlantDrawOptions {
  uint32_t maxSegments = 5;   // n_max of eq. 4: segments of a blade at full detail (1 … 16)
  float lodDistanceM = 4.0f;  // eq. 4's distance unit: full detail within it, n_max / d² beyond
  bool shadows = true;        // the planar shadows of §3.6
  // Shadows end here, fading out over the last quarter (shaders/common/plant_shape.glsl): far
  // shadows are streaks 1.5 pixels wide that cost more than their plants.
  float shadowDistanceM = 30.0f;
  bool fullDetail = false;    // every blade at n_max segments (tests, speed-of-light runs)
  // Every plant fragment flat magenta (#ff00ff, the shadows' screen door aside): where plants
  // cover the ground, measured against a frame without plants (`--plant-style coverage`).
  bool flatColour = false;
  // false: plants appear and vanish at full size — the fades by size (a sequence's end, a
  // species' horizon, the imagery cross-fade) and the segment morph off, to show what they hide
  // (`--plant-fades off`).
  bool fades = true;
  // The speed-of-light pipeline instead of each kind's: the same patches, blades and segments
  // with the simplest shaders (straight lines, constant colour, no shadows) — what the geometry
  // front end alone costs (bench/bench_plants.cpp).
  bool speedOfLight = false;
  // Tessellation or Compute for this frame; Auto: the renderer's (RendererOptions::bladePath).
  // The speed-of-light pipeline is a tessellation pipeline: with speedOfLight the path is
  // always Tessellation.
  BladePath path = BladePath::Auto;
};

struct VegetationRequest {
  std::span<const SeedTriangleGpu> triangles;
  uint32_t clusterSize = 8;
  PlantStyle style = PlantStyle::Plants;
  PlantDrawOptions draw;
  // Cull seed triangles hidden behind this frame's terrain depth (Hi-Z, render/hiz_pass.h)
  // before the classify pass expands them; off: every triangle is classified.
  bool occlusionCulling = true;
  // The crowns near the camera the triangles are relative to: the plants thin under them
  // (vegetation/canopy_cells.h). Null: no trees. Must stay alive until submitFrame returns.
  const vegetation::CanopyTable* canopy = nullptr;
};

struct FrameRequest {
  Camera camera;
  Lighting lighting;
  double cameraHeightMsl = 0.0;  // the atmosphere's LUTs are seen from this height
  bool readbackColor = false;
  bool readbackDepth = false;
  // An AOV frame (shaders/common/aov.glsl): the passes write vegetation coverage and species
  // instead of colour, nothing is tone-mapped, and FrameResult::aov comes back (the depth is read
  // back with it). Its colour read-back, if asked for, is meaningless.
  bool aov = false;
  bool present = false;  // to the window, when the renderer has one
  // Strength of the close-up terrain detail textures (render/detail_textures.h), 0 … 1;
  // 0 draws the terrain as the bare imagery at every distance.
  float terrainDetail = 1.0f;
  // Drawn over the resolved frame (after the scene, before read-back and present) as the GPU
  // pass "hud"; must stay alive until submitFrame returns. Null: no overlay.
  const OverlayDrawData* overlay = nullptr;
  // Terrain to draw and imagery to upload first; both spans (and the meshes) must stay alive
  // until submitFrame returns.
  std::span<const TerrainDraw> terrain;
  std::span<const ImageryUpload> imageryUploads;
  // Plants (after the terrain); null: none. The species come from Renderer::setSpeciesCatalog.
  const VegetationRequest* vegetation = nullptr;
  // The shared simulation's step for this frame (simulation/simulation.h); must stay alive until
  // submitFrame returns. Null: nothing moves.
  const simulation::GpuStep* simulation = nullptr;
  // Trees (issue 20, render/tree_layout.h): the pool's page uploads and counts, the levels of
  // detail; the models come from Renderer::setTreeModels. Null: no trees drawn.
  const TreeRequest* trees = nullptr;
};

struct ColorImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;  // sRGB, row-major from the top
};

struct DepthImage {
  uint32_t width = 0, height = 0;
  std::vector<float> depth;  // reverse-Z: 1 at the near plane, 0 at the far plane / sky
};

// The measurement AOVs of an AOV frame (FrameRequest::aov; render/aov_image.h decodes them), row-major from the top.
struct AovImage {
  uint32_t width = 0, height = 0;
  std::vector<float> distanceM;  // metres from the camera to what the pixel's first sample sees; 0 for sky
  std::vector<float> coverage;   // 0 … 1: the share of the pixel's samples covered by plants or trees
  std::vector<float> species;    // the catalog index + 1 of the vegetation covering the pixel; 0 for none
};

struct FrameResult {
  uint64_t frameIndex = 0;
  double cpuRecordMs = 0.0;
  GpuTimings gpu;
  uint64_t terrainTriangles = 0;                // triangles submitted by the terrain pass
  // The terrain's chunks (terrain_mesh.h) drawn and uploaded this frame, and the vertices copied
  // to the GPU (chunks' and the meshes' own; render/terrain_geometry_buffers.h). Zero when the
  // vertices are copied every frame (RendererOptions::residentTerrain false).
  uint64_t terrainChunksDrawn = 0, terrainChunksUploaded = 0, terrainVerticesUploaded = 0;
  // The terrain rasterised in compute (TerrainShading::Compute): what its binning made
  // (render/terrain_raster_pass.h); zero otherwise.
  bool terrainRasterised = false;
  uint64_t terrainRasterTriangles = 0;  // after culling and near clipping (a clipped triangle may be two)
  uint64_t terrainTileEntries = 0;      // triangle-in-tile entries its lists needed
  uint64_t terrainTileEntriesDropped = 0;  // past the lists' capacity (they grow for the next frames)
  // 8 × 8 tiles whose depth went into the attachment per pixel and per sample (where plants or
  // trees may be drawn: render/terrain_depth_handover.h)
  uint64_t terrainDepthTiles = 0, terrainDepthEdgeTiles = 0;
  std::optional<VegetationFigures> vegetation;  // when the request had plants
  std::optional<TreeFigures> trees;             // when the request had trees
  std::optional<ColorImage> color;
  std::optional<DepthImage> depth;
  std::optional<AovImage> aov;  // when the request was an AOV frame
  float exposureEv = 0.0f;  // the exposure (EV100) this frame was tone-mapped with
};

}  // namespace vegstream::render
