#include "flight/scene.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/stopwatch.h"
#include "streaming/dataset_snapshot.h"
#include "terrain/grid_mesh.h"
#include "terrain/snapshot_grid.h"

namespace vegstream::flight {

struct Scene::Impl {
  std::unique_ptr<render::Renderer> renderer;
  SceneInfo info;
  terrain::HeightGrid grid;
  geo::LocalFrame frame{geo::Geodetic{}};
  render::Lighting lighting;
};

Scene::Scene(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Scene::~Scene() = default;

Result<std::unique_ptr<Scene>> Scene::open(const SceneOptions& options) {
  const Logger log = options.logger ? options.logger : makeNullLogger();
  Stopwatch watch;
  // The dataset first, then the renderer with its options: both fail before anything is printed.
  std::error_code ec;
  if (!std::filesystem::is_directory(options.dataset, ec))
    return makeError(ErrorKind::NotFound, options.dataset.string() + ": no such dataset directory");
  streaming::SnapshotLimits limits;
  limits.maxHeightPixels = std::max<uint64_t>(4, options.maxMeshTriangles / 2);
  limits.maxImageryPixels = options.maxImageryPixels;
  auto snapshot = streaming::loadDatasetSnapshot(options.dataset, limits);
  if (!snapshot) return snapshot.error();
  auto renderer = render::Renderer::create(options.renderer);
  if (!renderer) return renderer.error();

  auto impl = std::make_unique<Impl>();
  impl->renderer = std::move(*renderer);
  impl->grid = terrain::heightGridFrom(snapshot->heights);
  const geo::GeoBounds& b = snapshot->meta.bounds;
  impl->frame = geo::LocalFrame({0.5 * (b.southDeg + b.northDeg), b.centre().x, 0.0});

  const bool hasImagery = snapshot->imagery.width > 0;
  terrain::GridMeshOptions meshOptions;
  if (hasImagery) meshOptions.uv = terrain::imageryUv(snapshot->imagery);
  const terrain::TerrainMesh mesh = terrain::buildGridMesh(impl->grid, impl->frame, meshOptions);
  render::ColorImage imagery;
  if (hasImagery) {
    imagery.width = static_cast<uint32_t>(snapshot->imagery.width);
    imagery.height = static_cast<uint32_t>(snapshot->imagery.height);
    imagery.rgba = std::move(snapshot->imagery.rgba);
  }
  if (Status s = impl->renderer->setTerrain(mesh, hasImagery ? &imagery : nullptr); !s) return s.error();

  SceneInfo& info = impl->info;
  info.datasetName = snapshot->meta.name;
  info.bounds = b;
  info.heightZoom = snapshot->heights.zoom;
  info.imageryZoom = hasImagery ? snapshot->imagery.zoom : -1;
  info.meshTriangles = mesh.triangleCount();
  info.cpuBytes = impl->grid.heights.size() * sizeof(float);  // the heights kept for ground queries
  info.gpuBytes = impl->renderer->gpuBytes();
  info.loadMs = watch.elapsedMs();
  log->debug("dataset {}: heights at zoom {} ({}x{}), imagery at zoom {}, {} triangles, {} tiles read ({:.0f} ms)",
            info.datasetName, info.heightZoom, impl->grid.width, impl->grid.height, info.imageryZoom,
            info.meshTriangles, snapshot->tilesRead, info.loadMs);
  return std::unique_ptr<Scene>(new Scene(std::move(impl)));
}

render::Renderer& Scene::renderer() { return *impl_->renderer; }
const SceneInfo& Scene::info() const { return impl_->info; }
const geo::LocalFrame& Scene::frame() const { return impl_->frame; }

double Scene::groundHeight(double latDeg, double lonDeg) const { return impl_->grid.sampleLonLat(lonDeg, latDeg); }

GroundHeight Scene::groundFunction() const {
  const Impl* impl = impl_.get();
  return [impl](double lat, double lon) { return impl->grid.sampleLonLat(lon, lat); };
}

render::FrameRequest Scene::frameRequest(const FlightSample& sample) const {
  render::FrameRequest req;
  const geo::LocalFrame& frame = impl_->frame;
  const glm::dvec3 position = frame.toLocal(sample.position);
  // Heading and pitch are relative to the local east/north/up at the camera, which tilts away
  // from the frame's axes with distance from its origin (earth curvature).
  const glm::dvec3 up = frame.upAt(sample.position);
  const glm::dvec3 northAhead =
      frame.toLocal({sample.position.latDeg + 1e-4, sample.position.lonDeg, sample.position.heightM});
  glm::dvec3 north = northAhead - position;
  north = glm::normalize(north - up * glm::dot(north, up));
  const glm::dvec3 east = glm::cross(north, up);
  const glm::dvec3 f = forwardVector(sample.headingDeg, sample.pitchDeg);  // in east/north/up terms
  req.camera.position = position;
  req.camera.forward = glm::normalize(east * f.x + north * f.y + up * f.z);
  req.camera.up = up;
  req.cameraHeightMsl = sample.position.heightM;
  req.lighting = impl_->lighting;
  return req;
}

}  // namespace vegstream::flight
