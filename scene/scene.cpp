// The composition root (scene.h): Scene::open builds the dataset's source, the renderer, the
// tile streamer, the streamed terrain and the trees; prepareFrame turns a flight sample into the
// frame's request (streaming, terrain, seeding, trees) and its figures.
#include "scene/dataset_calibration.h"
#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/capped_runner.h"
#include "core/stopwatch.h"
#include "core/task_runner.h"
#include "streaming/dataset_snapshot.h"
#include "streaming/open_tile_source.h"
#include "streaming/tile_check.h"
#include "scene/seeding_stage.h"
#include "scene/streaming_stage.h"
#include "scene/terrain_stage.h"
#include "scene/tree_field.h"
#include "scene/tree_stage.h"
#include "scene/tree_ground.h"
#include "streaming/disk_tile_cache.h"
#include "terrain/snapshot_grid.h"
#include "vegetation/philox.h"
#include "vegetation/plant_seeding.h"
#include "vegetation/tree_model.h"

namespace vegstream::scene {

struct Scene::Impl {
  std::unique_ptr<ThreadPool> tasks;  // the sources' I/O and the decodes; destroyed after them
  std::unique_ptr<CappedRunner> frameTasks;  // `tasks`, capped at options.frameWorkers for the frame's loops
  std::unique_ptr<streaming::DiskTileCache> impostorCache;  // the renderer's (outlives it)
  std::unique_ptr<render::Renderer> renderer;
  SceneOptions options;
  SceneInfo info;
  terrain::HeightGrid ground;
  geo::LocalFrame frame{geo::Geodetic{}};
  render::Lighting lighting;  // all but the sun's direction, which follows `sun`
  SunClock sun;
  std::shared_ptr<streaming::TileSource> source;
  std::unique_ptr<streaming::TileStreamer> streamer;
  std::unique_ptr<terrain::StreamedTerrain> terrain;
  std::unique_ptr<TreeGround> treeGround;
  std::unique_ptr<TreeField> treeField;
  // The scene's stages of the frame, in order (prepareFrame): streaming, terrain, seeding, trees.
  std::vector<std::unique_ptr<FrameStage>> stages;
  std::unique_ptr<FrameContext> lastContext;  // prepareFrame(pose, t, ahead)'s
  SceneFrameFigures figures;                  // the last prepared frame's
  vegetation::SpeciesCatalog catalog;  // the catalog with the dataset's colour calibration (trees point at it)

};

namespace {

// The impostors' cache (SceneTreeOptions::impostorCacheDir), or null: none asked for, trees off,
// or a directory that cannot be used (a warning).
std::unique_ptr<streaming::DiskTileCache> openImpostorCache(const SceneOptions& options, const Logger& log) {
  if (!options.trees.enabled || !options.trees.impostorCacheDir) return nullptr;
  auto cache = streaming::DiskTileCache::open(*options.trees.impostorCacheDir, options.trees.impostorCacheBytes, log,
                                             "impostor cache");
  if (!cache) {
    log->warn("{}; the impostors are captured without it", cache.error().message);
    return nullptr;
  }
  return std::move(*cache);
}

// How the impostors came, for the log line of openTrees.
std::string impostorSource(const render::ImpostorCacheFigures& c) {
  const double mb = static_cast<double>(c.fileBytes) / 1e6;
  if (c.hit) return fmt::format("impostors from the cache: {:.1f} MB in {:.0f} ms", mb, c.ms);
  if (c.stored) return fmt::format("impostors captured, then cached: {:.1f} MB in {:.0f} ms", mb, c.ms);
  return "impostors captured";
}

// The catalog's tree species as models (variants each, vegetation/tree_model.h), uploaded with
// their impostors; the ground mosaics the placement reads; the field of tiles around the camera.
Status openTrees(Scene::Impl& m, const datasets::DatasetMeta& meta, const streaming::SnapshotLimits& limits,
                 const vegetation::SpeciesCatalog& catalog) {
  Stopwatch watch;
  const SceneTreeOptions& o = m.options.trees;
  const uint32_t variants = std::max(o.variants, 1u);
  std::vector<render::TreeModelSet> sets;
  std::vector<uint32_t> firstModel(catalog.species.size(), UINT32_MAX);
  uint32_t models = 0;
  for (size_t s = 0; s < catalog.species.size(); ++s) {
    const vegetation::Species& sp = catalog.species[s];
    if (!vegetation::isTree(sp)) continue;
    if (models + variants > render::kMaxTreeModels) break;
    render::TreeModelSet set;
    set.species = static_cast<uint32_t>(s);
    set.params = sp.tree;
    const float height = 0.5f * (sp.heightM.min + sp.heightM.max);
    const float crown = 0.5f * (sp.widthM.min + sp.widthM.max);
    for (uint32_t v = 0; v < variants; ++v)
      set.variants.push_back(
          vegetation::buildTreeModel(sp.tree, height, crown, vegetation::philox(v, static_cast<uint32_t>(s), 0x74ee5u).x));
    firstModel[s] = models;
    models += variants;
    sets.push_back(std::move(set));
  }
  if (sets.empty()) return {};
  const double modelsMs = watch.elapsedMs();
  auto ground = TreeGround::load(*m.source, meta, m.frame, limits);
  if (!ground) return ground.error();
  if (meta.landcover) ground->allowLandcover(landcoverMasks(catalog, *meta.landcover));
  m.treeGround = std::make_unique<TreeGround>(std::move(*ground));
  const double groundMs = watch.elapsedMs() - modelsMs;
  if (Status s = m.renderer->setTreeModels(sets); !s) return s.error();
  const Logger& log = m.options.logger;
  if (log)
    log->debug("trees: {} models built in {:.0f} ms, ground mosaics {:.0f} ms, uploaded with impostors {:.0f} ms ({})",
               models, modelsMs, groundMs, watch.elapsedMs() - modelsMs - groundMs,
               impostorSource(m.renderer->impostorCacheFigures()));
  TreeFieldOptions fo;
  fo.lod = o.lod;
  fo.lod.horizonM = static_cast<float>(o.horizonM > 0.0 ? o.horizonM : vegetation::farthestTreeHorizon(catalog));
  fo.fades = o.fades;
  fo.shadows = o.shadows;
  fo.cores = o.cores;
  m.treeField = std::make_unique<TreeField>(catalog, m.treeGround->at(), fo, std::move(firstModel), variants,
                                            m.renderer->treePageCapacity());
  // Trees at the canopy layer's crowns (canopy_trees.h); a layer too large to read goes unused.
  auto canopy = CanopyTrees::load(*m.source, meta, m.frame);
  if (canopy)
    m.treeField->setCanopy(std::move(*canopy));
  else if (canopy.error().kind == ErrorKind::InvalidInput && log)
    log->warn("{}", canopy.error().message);
  else if (canopy.error().kind != ErrorKind::InvalidInput)
    return canopy.error();
  m.info.treeModels = models;
  m.info.treeSetupMs = watch.elapsedMs();
  return {};
}

// The tile streamer over the source, the scene's description, and the renderer's imagery layers.
Status openStreaming(Scene::Impl& m, const datasets::DatasetMeta& meta, int groundZoom, const Logger& log) {
  streaming::StreamingOptions streamingOptions = terrain::streamingOptionsFor(meta, m.options.streaming);
  streamingOptions.tasks = m.tasks.get();
  streamingOptions.maxGpuSlots = std::min(streamingOptions.maxGpuSlots, m.renderer->maxImageryLayers());
  SceneInfo& info = m.info;
  info.datasetName = meta.name;
  info.source = m.source->describe();
  info.bounds = meta.bounds;
  info.minZoom = meta.minZoom;
  info.maxZoom = meta.maxZoom;
  info.groundZoom = groundZoom;
  info.hasImagery = meta.imagery.has_value();
  info.groundBytes = m.ground.heights.size() * sizeof(float);
  m.streamer = std::make_unique<streaming::TileStreamer>(m.source, meta, streamingOptions, log);
  info.imageryLayers = info.hasImagery ? m.streamer->gpuSlotCount() : 0;
  if (info.hasImagery) {
    if (info.imageryLayers == 0)
      return makeError(ErrorKind::InvalidInput, "--gpu-budget-mb: too small for one imagery tile (256 KiB)");
    if (Status s = m.renderer->setImageryLayers(info.imageryLayers, {meta.ndvi, meta.landcover.has_value()}); !s)
      return s.error();
  }
  return {};
}

// The catalog calibrated to the dataset (and given to the renderer when it differs from the
// default), and the streamed terrain with the seeding it decides.
Status openTerrain(Scene::Impl& m, const datasets::DatasetMeta& meta) {
  m.catalog = calibratedCatalog(m.options.species ? *m.options.species : vegetation::defaultSpeciesCatalog(), meta);
  if (meta.landcover) m.catalog.landcoverCodes = landcoverMasks(m.catalog, *meta.landcover);
  if (m.options.species || !m.catalog.calibration.isIdentity() || m.catalog.landcoverCodes)
    if (Status s = m.renderer->setSpeciesCatalog(m.catalog); !s) return s.error();
  if (m.options.clusterSize < 1 || m.options.clusterSize > vegetation::kMaxClusterSize)
    return makeError(ErrorKind::InvalidInput, "--cluster-size " + std::to_string(m.options.clusterSize) +
                                                  ": must be 1 … " + std::to_string(vegetation::kMaxClusterSize));
  // The catalog decides how dense plants grow and how far the farthest can be seen: the seed
  // triangles' counts stop there (terrain/seed_triangles.h), each species at its own.
  const vegetation::SpeciesCatalog& catalog = m.catalog;
  terrain::SeedOptions& seeds = m.options.terrain.seeds;
  seeds.groundDensityM2 = vegetation::densestGroundDensity(catalog);
  seeds.horizonM = std::min<double>(seeds.horizonM, vegetation::farthestHorizon(catalog));
  m.options.terrain.roam.tasks = m.frameTasks.get();  // compactions beside the frame, and its loops
  m.terrain = std::make_unique<terrain::StreamedTerrain>(*m.streamer, m.frame, m.options.terrain);
  SceneInfo& info = m.info;
  info.seedLevel = m.terrain->roam().seedLevel();
  info.seedAreaM2 = terrain::triangleAreaM2(m.terrain->roam().mesh().grid(), info.seedLevel, meta.bounds.centre().y);
  return {};
}

}  // namespace

// The scene's part of the frame's list of stages (frame_stage.h); the driver's simulation and
// render stages follow them.
Scene::Scene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {
  Impl& m = *impl_;
  const bool settled = m.options.mode == StreamingMode::Settled;
  m.stages.push_back(std::make_unique<StreamingStage>(*m.streamer, *m.terrain, settled, m.info.groundBytes));
  m.stages.push_back(std::make_unique<TerrainStage>(*m.terrain));
  m.stages.push_back(std::make_unique<SeedingStage>(*m.terrain, m.options));
  if (m.treeField) m.stages.push_back(std::make_unique<TreeStage>(*m.treeField, *m.renderer, settled));
}
Scene::~Scene() = default;

Result<std::unique_ptr<Scene>> Scene::open(const SceneOptions& options) {
  const Logger log = options.logger ? options.logger : makeNullLogger();
  Stopwatch watch;
  // The dataset first, then the renderer with its options: both fail before tiles are read.
  auto tasks = std::make_unique<ThreadPool>();
  auto frameTasks = std::make_unique<CappedRunner>(
      *tasks, options.frameWorkers > 0 ? options.frameWorkers : std::numeric_limits<int>::max());
  streaming::OpenSourceOptions so;
  so.http.cacheDir = options.httpCacheDir;
  so.http.allowRedirects = options.httpAllowRedirects;
  so.http.requestDeadlineMs = options.httpRequestDeadlineMs;
  so.log = log;
  so.tasks = tasks.get();
  auto source = streaming::openTileSource(options.dataset, so);
  if (!source) return source.error();
  auto meta = streaming::readMetaFrom(**source);
  if (!meta) return meta.error();
  // Only tiles that decode as this dataset's are kept in the HTTP cache (tile_check.h).
  if (auto* http = dynamic_cast<streaming::HttpTileSource*>(source->get()))
    http->setTileCheck(streaming::tileCheckFor(*meta, http->describe()));
  const geo::GeoBounds& b = meta->bounds;
  const double centreLat = 0.5 * (b.southDeg + b.northDeg), centreLon = b.centre().x;
  auto sun = resolveSunClock(options.datetime, meta->imageryDatetime, streaming::datasetJsonName(**source), centreLat,
                             centreLon);
  if (!sun) return sun.error();
  std::unique_ptr<streaming::DiskTileCache> impostorCache = openImpostorCache(options, log);
  render::RendererOptions rendererOptions = options.renderer;
  rendererOptions.impostorCache = impostorCache.get();
  rendererOptions.tasks = frameTasks.get();
  rendererOptions.terrainTriangles = options.terrain.roam.maxTriangles;
  rendererOptions.trailStoreBytes = static_cast<uint64_t>(options.simulation.trailBudgetMb * 1024.0 * 1024.0);
  auto renderer = render::Renderer::create(rendererOptions);
  if (!renderer) return renderer.error();

  auto impl = std::make_unique<Impl>();
  impl->tasks = std::move(tasks);
  impl->frameTasks = std::move(frameTasks);
  impl->impostorCache = std::move(impostorCache);
  impl->options = options;
  impl->renderer = std::move(*renderer);
  impl->source = std::move(*source);  // the source goes before the pool its tasks run on
  streaming::SnapshotLimits limits;
  limits.maxHeightPixels = options.groundMaxPixels;
  limits.log = log;
  auto ground = streaming::loadGroundHeights(*impl->source, *meta, limits);
  if (!ground) return ground.error();
  impl->ground = terrain::heightGridFrom(*ground);
  impl->frame = geo::LocalFrame({centreLat, centreLon, 0.0});
  impl->sun = *sun;
  impl->lighting.exposureEv = options.exposureEv;

  if (Status s = openStreaming(*impl, *meta, ground->zoom, log); !s) return s.error();
  SceneInfo& info = impl->info;
  if (Status s = openTerrain(*impl, *meta); !s) return s.error();
  const vegetation::SpeciesCatalog& catalog = impl->catalog;
  if (options.trees.enabled && info.hasImagery)
    if (Status s = openTrees(*impl, *meta, limits, catalog); !s) return s.error();
  info.loadMs = watch.elapsedMs();
  log->debug("dataset {} from {}: zooms {}…{}, ground at zoom {}, {} imagery layers ({:.0f} ms)", info.datasetName,
             info.source, info.minZoom, info.maxZoom, info.groundZoom, info.imageryLayers, info.loadMs);
  return std::unique_ptr<Scene>(new Scene(std::move(impl)));
}

const char* toString(StreamingMode mode) { return mode == StreamingMode::Settled ? "settled" : "realtime"; }

render::Renderer& Scene::renderer() { return *impl_->renderer; }
const render::Renderer& Scene::renderer() const { return *impl_->renderer; }
const SceneOptions& Scene::options() const { return impl_->options; }
const SceneInfo& Scene::info() const { return impl_->info; }
const geo::LocalFrame& Scene::frame() const { return impl_->frame; }
const SceneFrameFigures& Scene::lastFrameFigures() const { return impl_->figures; }
const SunClock& Scene::sunClock() const { return impl_->sun; }
void Scene::setStartDatetime(const geo::DateTime& start) { impl_->sun.start = start; }

render::Lighting Scene::lightingAt(double timeS) const {
  render::Lighting l = impl_->lighting;
  l.sunDirection = geo::sunDirectionEnu(impl_->sun.sunAt(timeS));
  return l;
}

bool Scene::waitForTileArrivals(std::chrono::milliseconds timeout) { return impl_->streamer->waitForArrivals(timeout); }
streaming::TileStreamer::IoProgress Scene::tileIoProgress() const { return impl_->streamer->ioProgress(); }

double Scene::groundHeight(double latDeg, double lonDeg) const { return impl_->ground.sampleLonLat(lonDeg, latDeg); }

GroundHeight Scene::groundFunction() const {
  const Impl* impl = impl_.get();
  return [impl](double lat, double lon) { return impl->ground.sampleLonLat(lon, lat); };
}

FrameContext Scene::frameContext(const FlightSample& now, double timeS, std::span<const FlightSample> ahead) const {
  const render::Renderer& r = *impl_->renderer;
  return FrameContext(impl_->frame, now, timeS, impl_->options.lookAhead ? ahead : std::span<const FlightSample>{},
                      static_cast<double>(r.width()), static_cast<double>(r.height()));
}

render::FrameRequest Scene::cameraRequest(const FrameContext& context) const {
  render::FrameRequest req;
  req.camera = context.camera;
  req.cameraHeightMsl = context.pose.position.heightM;
  req.terrainDetail = impl_->options.terrainDetail;
  req.lighting = lightingAt(0.0);
  return req;
}

render::FrameRequest Scene::prepareFrame(const FlightSample& now, double timeS, std::span<const FlightSample> ahead) {
  const render::Renderer& r = *impl_->renderer;
  impl_->lastContext = std::make_unique<FrameContext>(impl_->frame, now, timeS,
                                                      impl_->options.lookAhead ? ahead : std::span<const FlightSample>{},
                                                      static_cast<double>(r.width()), static_cast<double>(r.height()));
  prepareFrame(*impl_->lastContext);
  return impl_->lastContext->request;
}

void Scene::prepareFrame(FrameContext& context) {
  context.request = cameraRequest(context);
  context.request.lighting = lightingAt(context.timeS);
  for (const std::unique_ptr<FrameStage>& stage : impl_->stages) stage->run(context);
  impl_->figures = context.figures;
}

}  // namespace vegstream::scene
