// The species pipelines against their speed of light (render/plant_pass.h): one frame of a flat
// grass field (tests/support/plant_field_scene.h) at 640 × 360, MSAA 4, every blade at 5
// segments, rendered
//   - BM_Frame/terrain: the field without plants (what the rest of the frame costs);
//   - BM_Frame/plants: the grass pipeline with planar shadows (the default);
//   - BM_Frame/plants_no_shadows;
//   - BM_Frame/speed_of_light: the same patches, blades and segments through the simplest shaders
//     (straight lines, constant colour, no shadows).
// Manual time = the GPU frame time (timestamps; on lavapipe the frame total is what is
// meaningful). Counters: plants, plant triangles, ms per million blades over the terrain-only
// frame. The ratio plants / speed_of_light comes from one run.
//
//   build/release/bench/bench_plants [--benchmark_filter=…] [VEGSTREAM_DEVICE=name]
//   VEGSTREAM_BENCH_SIZE=1920x1080 for a real GPU

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>

#include "render/renderer.h"
#include "tests/support/plant_field_scene.h"

namespace {

using namespace vegstream;
using namespace vegstream::render;

enum Case { kTerrain, kPlants, kPlantsNoShadows, kSpeedOfLight };

Renderer* renderer() {
  static std::unique_ptr<Renderer> r = [] {
    RendererOptions o;
    o.width = 640;
    o.height = 360;
    if (const char* s = std::getenv("VEGSTREAM_BENCH_SIZE")) std::sscanf(s, "%ux%u", &o.width, &o.height);
    o.msaa = 4;
    if (const char* d = std::getenv("VEGSTREAM_DEVICE")) o.context.deviceName = d;
    auto created = Renderer::create(o);
    if (!created) {
      std::fprintf(stderr, "bench_plants: %s\n", created.error().message.c_str());
      return std::unique_ptr<Renderer>();
    }
    if (!(*created)->setImageryLayers(1)) return std::unique_ptr<Renderer>();
    return std::move(*created);
  }();
  return r.get();
}

void BM_Frame(benchmark::State& state) {
  Renderer* r = renderer();
  if (!r) {
    state.SkipWithError("no renderer");
    return;
  }
  const auto which = static_cast<Case>(state.range(0));
  const std::array<uint8_t, 3> c = testing::referenceColour("grass");
  const std::vector<uint8_t> tile = testing::flatTile(c[0], c[1], c[2]);
  const ImageryUpload upload{0, tile.data()};
  terrain::TerrainMesh plane = testing::flatPlane(testing::kField, 8, 0.0f);
  for (auto& v : plane.vertices) v.uv = testing::fieldUv(v.position.x, v.position.y);
  TerrainDraw draw{&plane};
  draw.imageryLayer = 0;
  FrameRequest req;
  req.camera.position = {0.0, 0.0, 2.0};
  req.camera.forward = glm::normalize(glm::dvec3(0.0, 1.0, -0.35));
  req.camera.up = {0.0, 0.0, 1.0};
  req.cameraHeightMsl = 2.0;
  req.terrain = {&draw, 1};
  req.imageryUploads = {&upload, 1};
  const std::vector<SeedTriangleGpu> seeds = testing::seedTriangles(req.camera.position, 24.0f);
  VegetationRequest plants{seeds, 8, PlantStyle::Plants, {}};
  plants.draw.maxSegments = 5;
  plants.draw.fullDetail = true;
  plants.draw.shadows = which == kPlants;
  plants.draw.speedOfLight = which == kSpeedOfLight;
  if (which != kTerrain) req.vegetation = &plants;
  auto warm = r->renderFrame(req);  // uploads the tile; pipelines warm
  if (!warm) {
    state.SkipWithError(warm.error().message.c_str());
    return;
  }
  req.imageryUploads = {};
  uint64_t plantCount = 0, triangles = 0;
  for (auto _ : state) {
    auto f = r->renderFrame(req);
    if (!f) {
      state.SkipWithError(f.error().message.c_str());
      return;
    }
    state.SetIterationTime(f->gpu.frameMs / 1000.0);
    if (f->vegetation) plantCount = f->vegetation->plantsTotal;
    triangles = f->gpu.statistics.geometryPrimitives;
  }
  state.counters["plants"] = static_cast<double>(plantCount);
  state.counters["plant_triangles"] = static_cast<double>(triangles);
  state.SetLabel(r->device().name);
}

BENCHMARK(BM_Frame)
    ->ArgName("case")
    ->Arg(kTerrain)
    ->Arg(kPlants)
    ->Arg(kPlantsNoShadows)
    ->Arg(kSpeedOfLight)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace
