#pragma once
// The renderer: the one object callers above render/ use. It owns the Vulkan context, the
// offscreen targets, the passes and kFramesInFlight frame slots (render/frame_slots.h: 3), each
// with its command buffer, fence, uniform buffer, GPU timer and read-back buffers; one deletion
// queue retires what a frame replaced once that frame has completed.
//
// Contract: create() validates the size and MSAA against the device and returns an Error
// naming the option; every GPU failure after that comes back as ErrorKind::Gpu.

#include <memory>
#include <string>

#include "core/result.h"
#include "core/task_runner.h"
#include "render/atmosphere_luts.h"
#include "render/context_options.h"
#include "render/frame_slots.h"
#include "render/frame_types.h"
#include "render/impostor_atlas_file.h"
#include "simulation/shared_code.h"
#include "terrain/terrain_mesh.h"

struct GLFWwindow;

namespace vegstream::streaming {
class DiskTileCache;
}

namespace vegstream::render {

// How the terrain is shaded (render/terrain_pass.h). Deferred: a visibility pass, then one
// compute dispatch shades every pixel (terrain and sky) into the colour target — needs storage
// images at the target's sample count. Forward: the terrain's fragments are shaded as drawn.
// Compute: rasterised in compute as well (render/terrain_raster_pass.h: no graphics work for the
// terrain but one full-screen pass that writes its depth samples into the depth attachment) —
// needs what deferred needs, and above one sample sampleRateShading.
// Auto: compute on a GPU (the fastest on the H200, measured), deferred on a CPU rasteriser, else
// forward. The images are the same up to rounding.
enum class TerrainShading { Auto, Forward, Deferred, Compute };
const char* terrainShadingName(TerrainShading shading);  // "auto", "forward", "deferred", "compute"
// What `asked` becomes on `device` at `msaa` samples (Auto resolved as above), or an
// InvalidInput error naming the option, the device and what it lacks.
Result<TerrainShading> resolveTerrainShading(TerrainShading asked, const DeviceInfo& device, int msaa);

struct RendererOptions {
  ContextOptions context;
  uint32_t width = 640;
  uint32_t height = 360;
  int msaa = 4;
  TerrainShading terrainShading = TerrainShading::Auto;
  // How plants become triangles (frame_types.h): Auto picks Compute; Mesh is refused by create()
  // (this build has no mesh-shader path) with an InvalidInput error naming the device.
  BladePath bladePath = BladePath::Auto;
  // The compute blade path's ceiling per frame slot, in vertices (32 bytes each; indices 3 × and
  // plants ¼ × as many): buffers grow to each frame's bound up to it, and plants past it
  // are dropped and counted (VegetationFigures::bladesDropped). Default 8 Mi (256 MiB); at least 6.
  uint32_t bladeMaxVertices = 1u << 23;
  // The shared simulation's trail store (render/simulation_pass.h): SimulationOptions::trailBudgetMb.
  uint64_t trailStoreBytes = uint64_t{16} << 20;
  // The trees' GPU memory (render/tree_pass.h): models, impostor atlas, visible lists and the
  // instance pool, which gets what the rest leaves (`--tree-budget-mb`). 256 MiB: the default
  // catalog's six tree species, three variants each, take about 100 MiB of meshes and impostors
  // (tree_models.cpp); with 128 the default flight refused to start (issue 41 item 4).
  uint64_t treeBudgetBytes = uint64_t{256} << 20;
  // Where the trees' impostors are kept between processes (render/impostor_atlas_cache.h:
  // looked up before a capture, stored after one); null: captured every time. Must outlive the
  // renderer.
  streaming::DiskTileCache* impostorCache = nullptr;
  // Texels per side of each of the sun shadow map's cascades (render/shadow_cascades.h).
  uint32_t shadowMapSize = 1024;
  // How the trees' shadow rasteriser (shaders/tree_shadow_raster.comp) shares out its work, for
  // tests (the map must not depend on it): the workgroups of a cascade's dispatch (0: the
  // device's, 4096 on a GPU, 64 on a CPU rasteriser; else at least 16) and the layers among them
  // that share a caster's 8 × 8 texel blocks (0: as each cascade's texel size asks; else 1–16).
  uint32_t treeShadowGroups = 0;
  uint32_t treeShadowLayers = 0;
  GLFWwindow* window = nullptr;  // present to this window's surface when set
  // The terrain triangles a frame may draw (the ROAM budget, terrain::RoamOptions::maxTriangles):
  // the terrain pass's geometry buffers start that large, so they do not grow — a new buffer
  // allocated and mapped, 1–4 ms on the H200 — while a flight refines; 0: they start small.
  uint64_t terrainTriangles = 0;
  // The terrain's vertices stay on the GPU, ROAM's chunks uploaded only when new or moved
  // (render/terrain_geometry_buffers.h); false: every frame copies them all (the images are the
  // same byte for byte; `--terrain-geometry copied`, for comparison).
  bool residentTerrain = true;
  // With the terrain rasterised in compute: where its depth goes into the depth attachment
  // (render/terrain_depth_handover.h; `--terrain-depth-tiles`).
  DepthTiles depthTiles = DepthTiles::Vegetation;
  // Where the per-frame CPU work shares out (the terrain pass's copies; render/terrain_pass.h),
  // with the thread that submits; null: all on that thread. Must outlive the renderer.
  TaskRunner* tasks = nullptr;
};

class Renderer {
 public:
  static Result<std::unique_ptr<Renderer>> create(const RendererOptions& options);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const DeviceInfo& device() const;
  uint32_t width() const;
  uint32_t height() const;
  int msaa() const;
  TerrainShading terrainShading() const;  // Forward, Deferred or Compute: what Auto resolved to
  // The blade path frames use unless they ask for another: Tessellation or Compute, never Auto.
  BladePath bladePath() const;
  bool hasWindow() const;
  const ValidationLog* validationLog() const;

  // The imagery texture array gets `layers` 256 × 256 layers (FrameRequest::imageryUploads fill
  // them); waits for frames in flight. 1 … maxImageryLayers(), else an InvalidInput error.
  // With companions each layer also holds its tile's NDVI (ImageryUpload::ndvi: a dataset
  // imported with --imagery-nir) and landcover classes (::landcover: --landcover), which the
  // species choice then reads (the classes through the catalog's landcoverCodes).
  Status setImageryLayers(uint32_t layers, ImageryCompanions companions = {});
  uint32_t imageryLayers() const;
  uint32_t maxImageryLayers() const;  // the device's maxImageArrayLayers
  // The species the classify pass sorts plants into (the default catalog until set); waits for
  // frames in flight.
  Status setSpeciesCatalog(const vegetation::SpeciesCatalog& catalog);
  // The tree models (every species' variants), uploaded and captured as impostors at once; the
  // instance pool is sized from RendererOptions::treeBudgetBytes. Waits for frames in flight.
  // InvalidInput when the budget does not hold the models and their atlas (naming the budget).
  Status setTreeModels(std::span<const TreeModelSet> sets);
  // Pages of kTreePageSize trees the pool holds (0 before setTreeModels); the trees' GPU bytes.
  uint32_t treePageCapacity() const;
  uint64_t treeGpuBytes() const;
  // What the last setTreeModels did with RendererOptions::impostorCache.
  const ImpostorCacheFigures& impostorCacheFigures() const;
  // One model's impostor atlas layer (RGBA8 albedo + coverage, kImpostorViews × kImpostorCellPx
  // square at mip level 0, half as wide at each next level), for tests; waits for the GPU.
  Result<std::vector<uint8_t>> readTreeImpostor(uint32_t model, uint32_t level = 0);
  // Model `model`'s trees drawn at mesh level `lod` (0 full, 1 reduced) in the last frame, as
  // instance indices in draw order (nearest first: shaders/tree_sort.comp), for tests; waits for
  // the GPU.
  Result<std::vector<uint32_t>> readTreeList(uint32_t model, uint32_t lod);
  // The sun shadow map as the last frame left it: every cascade's layer, shadowMapSize² texels
  // each, row by row, as reverse-Z depth bits (0: nothing casts there), for tests; waits for the
  // GPU.
  Result<std::vector<uint32_t>> readSunShadowMap();
  // Bytes of the scene's GPU buffers and textures (targets excluded).
  uint64_t gpuBytes() const;
  // The shared simulation's GPU state as it is now (waits for the GPU to be idle): the wind cells
  // (simulation::shader::WindCellGpu, 128 × 128, toroidal) and the interaction field (vec4 texels,
  // tile-major: render/simulation_pass.h). For tests and inspection; every frame is finished first.
  struct SimulationReadback {
    std::vector<simulation::shader::WindCellGpu> windCells;
    std::vector<glm::vec4> field;
  };
  Result<SimulationReadback> readSimulation();
  // The vertices the compute blade path wrote in the last frame (waits for the GPU to be idle):
  // shaders/common/blade_layout.glsl's BladeVertex, in the order written. Empty when that frame
  // did not expand blades. For tests (segment morphs, vertex positions).
  struct BladeVertexReadback {
    glm::vec3 pos;  // camera-relative
    uint32_t plant; // bits 0–28 the plant record, 29–30 kind, 31 shadow
    uint32_t colour[2];
    uint32_t blade;  // packSnorm2x16(across, along)
    uint32_t species;  // the plant's catalog index
  };
  Result<std::vector<BladeVertexReadback>> readBladeVertices();
  // The atmosphere's LUTs and sky light as the last frame left them (render/atmosphere_pass.h).
  Result<AtmosphereLuts> readAtmosphere();
  // The shared simulation's GPU memory: fixed at start-up, whatever the plants drawn.
  uint64_t simulationGpuBytes() const;

  // Records and submits one frame; returns its index. Does not wait for the GPU, except for the
  // frame that last used the slot (index − kFramesInFlight), when it has not been waited for.
  Result<uint64_t> submitFrame(const FrameRequest& request);
  // Waits for frame `index` (any of the last kFramesInFlight submitted, in any order) and
  // returns its figures and the read-backs it asked for; another index is an Internal error.
  Result<FrameResult> waitFrame(uint64_t index);
  // submitFrame + waitFrame.
  Result<FrameResult> renderFrame(const FrameRequest& request);

  struct Impl;

 private:
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vegstream::render
