#pragma once
// The composition root: a dataset opened for flying — its tiles streamed from a directory or
// an HTTP server under memory budgets (streaming/), the terrain drawn from whatever is resident
// (terrain/streamed_terrain.h), the renderer, and the conversion from flight samples to render
// frames. Frames are run by the frame driver (frame_driver.h), never assembled elsewhere.
//
// Per frame: prepareFrame(sample, t, ahead) — the terrain says which tiles it wants for this
// camera and (look-ahead) for the poses expected next; the streamer updates (realtime: never
// waits; settled: waits until the wanted tiles are resident, the wait measured apart); imagery
// uploads are planned; the terrain becomes draws. The returned request is valid until the next
// prepareFrame.
//
// The ground under scripted paths (terrain-relative altitudes) comes from a fixed height
// mosaic read at open(), so the same path gives the same poses whatever is streamed.
//
// Contract: open() checks the dataset and every renderer option before loading tiles, and
// returns user mistakes as errors whose message names the dataset or option.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "core/log.h"
#include "core/result.h"
#include "flight/ground_height.h"
#include "flight/path_sampler.h"
#include "geo/bounds.h"
#include "geo/datetime.h"
#include "geo/local_frame.h"
#include "render/renderer.h"
#include "scene/frame_context.h"
#include "scene/sun_clock.h"
#include "scene/scene_frame_figures.h"
#include "simulation/simulation_options.h"
#include "streaming/tile_streamer.h"
#include "terrain/streamed_terrain.h"

namespace vegstream::scene {

using flight::FlightSample;
using flight::GroundHeight;

enum class StreamingMode {
  Realtime,  // I/O races the frames, as in interactive flight: fallbacks are drawn and counted
  Settled,   // each frame waits until the tiles it wants are resident (the wait is reported apart)
};

// "settled" / "realtime".
const char* toString(StreamingMode mode);

// Trees (issue 20): placed per world tile from the ground mosaics (scene/tree_field.h), drawn by
// the renderer's tree pass within its budget (RendererOptions::treeBudgetBytes).
struct SceneTreeOptions {
  bool enabled = true;
  double horizonM = 0.0;  // where trees end; 0: the catalog's farthest tree horizon
  uint32_t variants = 3;  // models per species, each tree picks one by its seed
  render::TreeLodDistances lod;  // its horizonM is set from the above
  bool fades = true;
  bool shadows = true;  // the trees cast into the cascaded sun shadow map
  bool cores = true;    // the crowns' opaque cores are drawn (vegetation/tree_core.h)
  // Where the models' impostors are kept between runs (render/impostor_atlas_cache.h; the app's
  // --impostor-cache); none: captured at every start. A directory that cannot be used is a
  // warning, never a failure.
  std::optional<std::filesystem::path> impostorCacheDir;
  uint64_t impostorCacheBytes = uint64_t{1} << 30;  // its byte budget (the least recently used go first)
};

struct SceneOptions {
  std::string dataset;  // a dataset directory or an http(s):// URL of one
  render::RendererOptions renderer;
  streaming::StreamingOptions streaming;
  terrain::StreamedTerrainOptions terrain;
  StreamingMode mode = StreamingMode::Realtime;
  bool lookAhead = true;       // prefetch the tiles of the poses expected next
  float terrainDetail = 1.0f;  // close-up detail textures, 0 (bare imagery) … 1
  std::optional<std::filesystem::path> httpCacheDir;
  bool httpAllowRedirects = false;  // --allow-redirects: follow redirects to other hosts (http(s) only)
  long httpRequestDeadlineMs = 30'000;  // --http-timeout-s: one HTTP request, all its retries included
  // --frame-workers: the most workers the frame's own parallel loops (ROAM, the terrain's copies)
  // use beside the frame thread (core/capped_runner.h); 0: every worker of the scene's pool.
  int frameWorkers = 0;
  uint64_t groundMaxPixels = 4'000'000;  // the ground mosaic for path altitudes
  // Plants: the seed triangles go to the classify pass each frame (render/classify_pass.h).
  bool plants = true;
  uint32_t clusterSize = 8;  // C, 1 … vegetation::kMaxClusterSize
  render::PlantStyle plantStyle = render::PlantStyle::Plants;
  render::PlantDrawOptions plantDraw;
  bool occlusionCulling = true;  // Hi-Z culling of hidden seed triangles (render/hiz_pass.h)
  std::shared_ptr<const vegetation::SpeciesCatalog> species;  // null: the default catalog
  // The shared simulation (wind, colliders, trails) every FrameDriver over this scene runs.
  simulation::SimulationOptions simulation;
  SceneTreeOptions trees;
  // The sun (issue 39, sun_clock.h): the date-time at flight time 0 (`--datetime`, else the
  // flight path's "datetime"); absent: the imagery's acquisition time, else the fixed default.
  std::optional<geo::DateTime> datetime;
  std::optional<float> exposureEv;  // `--exposure EV` (EV100); absent: automatic
  Logger logger;                    // may be null
};

struct SceneInfo {
  std::string datasetName;
  std::string source;  // "dir …" or the URL
  geo::GeoBounds bounds;
  int minZoom = 0, maxZoom = 0;
  int groundZoom = 0;  // zoom of the ground mosaic
  bool hasImagery = false;
  uint32_t imageryLayers = 0;  // GPU imagery slots (from the GPU budget)
  uint64_t groundBytes = 0;    // the ground mosaic on the CPU
  int seedLevel = 0;           // the bintree level of the seed triangles
  double seedAreaM2 = 0.0;     // their ground area at the dataset's centre
  uint32_t treeModels = 0;     // tree models built (species × variants); 0: no trees
  double treeSetupMs = 0.0;    // building them, their impostors and the ground mosaics
  double loadMs = 0.0;
};

class Scene {
 public:
  static Result<std::unique_ptr<Scene>> open(const SceneOptions& options);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  render::Renderer& renderer();
  const render::Renderer& renderer() const;
  const SceneOptions& options() const;
  const SceneInfo& info() const;
  const geo::LocalFrame& frame() const;  // ENU at the dataset's centre, height 0

  // Ground height (m MSL) under a point, bilinear over the ground mosaic; NaN outside the data.
  double groundHeight(double latDeg, double lonDeg) const;
  GroundHeight groundFunction() const;  // the same, for PathSampler

  // The views of a camera at `now` (flight time timeS) and of the poses expected next (look-ahead;
  // ignored when SceneOptions::lookAhead is off), for this scene's renderer (frame_context.h).
  FrameContext frameContext(const FlightSample& now, double timeS, std::span<const FlightSample> ahead = {}) const;
  // The scene's stages of the frame (frame_stage.h), in order: streaming, terrain, seeding and,
  // with trees, trees — after the context's request gets its camera and the sun at its time. The
  // driver runs its simulation and render stages after them.
  void prepareFrame(FrameContext& context);
  // The same for a pose, the context kept until the next call; the request it returns is valid as
  // long. Read-backs, presenting and the overlay are the caller's to set on it.
  render::FrameRequest prepareFrame(const FlightSample& now, double timeS, std::span<const FlightSample> ahead = {});
  const SceneFrameFigures& lastFrameFigures() const;  // the last prepared frame's
  // Realtime: waits until a tile request has finished (the next prepareFrame takes it in) or
  // `timeout` passes; true when one has. Lets a caller hold a pose until its tiles are in
  // without sleeping (TileStreamer::waitForArrivals).
  bool waitForTileArrivals(std::chrono::milliseconds timeout);
  // Any thread: the streamer's tile I/O under way (TileStreamer::ioProgress), for a caller that
  // steps a manual clock and lets each step's I/O settle before the next frame.
  streaming::TileStreamer::IoProgress tileIoProgress() const;

  // Camera and lighting for a context, without streaming or terrain; the sun of flight time 0.
  render::FrameRequest cameraRequest(const FrameContext& context) const;

  // The date-time and sun at every flight time (sun_clock.h), resolved at open().
  const SunClock& sunClock() const;
  // The date-time at flight time 0 from now on (the window's time-of-day keys and slider).
  void setStartDatetime(const geo::DateTime& start);
  // The frame's lighting at flight time timeS: the sun's direction (local ENU at the dataset's
  // centre) and SceneOptions::exposureEv. prepareFrame puts it in every request.
  render::Lighting lightingAt(double timeS) const;

  struct Impl;

 private:
  explicit Scene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// The frame's seed triangles as the classify pass reads them: camera-relative, with their keys
// and imagery; triangles without imagery are left out.
void seedTrianglesForGpu(std::span<const terrain::SeedTriangle> seeds, const glm::dvec3& camera,
                         std::vector<render::SeedTriangleGpu>& out);

}  // namespace vegstream::scene
