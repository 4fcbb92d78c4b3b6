// The species pipelines against their speed of light (render/plant_pass.h): one frame of a flat
// grass field (tests/support/plant_field_scene.h) at 640 × 360, MSAA 4, every blade at 5
// segments, rendered
//   - BM_Frame/terrain: the field without plants (what the rest of the frame costs);
//   - case 1: the tessellation path (grass pipeline) with planar shadows;
//   - case 2: the tessellation path without shadows;
//   - case 3: the speed of light: the same patches, blades and segments through the simplest
//     shaders (straight lines, constant colour, no shadows);
//   - case 4: the compute blade path (render/blade_pass.h) with planar shadows: the same blades,
//     expanded once per plant in compute and drawn by a trivial vertex stage;
//   - case 5: the compute path without shadows (the like-for-like against the speed of light);
//   - cases 6–8 (issue 19): the shared simulation with an 8 m/s gusty wind — the field alone
//     (terrain + the simulation pass), then cases 2 and 5 with every blade solving its
//     equilibrium under the wind: wind on against off, on both blade paths, in one run.
// Manual time = the GPU frame time (timestamps; on lavapipe the frame total is what is
// meaningful). Counters: plants (blades), plant triangles (geometry-stage primitives, or the
// compute path's own count). After the run, a table on stdout: each case's vegetation ms (case −
// terrain), its ratio to the speed of light's, and millions of blades per second — the ratio
// (compute − terrain) / (speed of light − terrain) comes from one run.
//
//   build/release/bench/bench_plants [--benchmark_filter=…] [VEGSTREAM_DEVICE=name]
//   (on a busy machine: --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true;
//   the table sums every repetition)
//   VEGSTREAM_BENCH_SIZE=1920x1080 for a real GPU

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>

#include "render/renderer.h"
#include "simulation/simulation.h"
#include "tests/support/plant_field_scene.h"

namespace {

using namespace vegstream;
using namespace vegstream::render;

enum Case { kTerrain, kPlants, kPlantsNoShadows, kSpeedOfLight, kCompute, kComputeNoShadows, kTerrainWind,
            kPlantsWind, kComputeWind };
const char* kCaseNames[] = {"terrain only",        "tessellation",         "tessellation, no shadows",
                            "speed of light",      "compute",              "compute, no shadows",
                            "terrain + simulation", "tessellation, wind",   "compute, wind"};
bool windy(Case c) { return c == kTerrainWind || c == kPlantsWind || c == kComputeWind; }

struct CaseFigures {
  double ms = 0.0;  // GPU ms summed over iterations
  uint64_t iterations = 0, plants = 0, triangles = 0;
};
std::map<int, CaseFigures>& figures() {
  static std::map<int, CaseFigures> f;
  return f;
}

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
  const ImageryUpload upload{0, tile};
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
  plants.draw.shadows = which == kPlants || which == kCompute;
  plants.draw.speedOfLight = which == kSpeedOfLight;
  plants.draw.path = which == kCompute || which == kComputeNoShadows || which == kComputeWind ? BladePath::Compute
                                                                                              : BladePath::Tessellation;
  if (which != kTerrain && which != kTerrainWind) req.vegetation = &plants;
  // The wind: an 8 m/s gusty westerly, stepped at 60 Hz (simulation/simulation.h).
  simulation::Simulation sim({.wind = {.speedMps = 8.0, .directionDeg = 270.0, .gustiness = 0.7}});
  double simTime = 0.0;
  const auto stepWind = [&] {
    if (!windy(which)) return;
    sim.step({.timeS = simTime, .dtS = simTime > 0.0 ? 1.0 / 60.0 : 0.0, .camera = req.camera.position});
    simTime += 1.0 / 60.0;
    req.simulation = &sim.gpuStep();
  };
  stepWind();
  auto warm = r->renderFrame(req);  // uploads the tile; pipelines warm
  if (!warm) {
    state.SkipWithError(warm.error().message.c_str());
    return;
  }
  req.imageryUploads = {};
  uint64_t plantCount = 0, triangles = 0;
  CaseFigures& fig = figures()[which];
  // Summed over every run of the case (--benchmark_repetitions, random interleaving).
  for (auto _ : state) {
    stepWind();
    auto f = r->renderFrame(req);
    if (!f) {
      state.SkipWithError(f.error().message.c_str());
      return;
    }
    state.SetIterationTime(f->gpu.frameMs / 1000.0);
    if (f->vegetation) plantCount = f->vegetation->plantsTotal;
    triangles = f->vegetation && f->vegetation->bladeCounts ? f->vegetation->bladeTriangles
                                                            : f->gpu.statistics.geometryPrimitives;
    fig.ms += f->gpu.frameMs;
    ++fig.iterations;
  }
  fig.plants = plantCount;
  fig.triangles = triangles;
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
    ->Arg(kCompute)
    ->Arg(kComputeNoShadows)
    ->Arg(kTerrainWind)
    ->Arg(kPlantsWind)
    ->Arg(kComputeWind)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

// Each case's vegetation cost (its mean GPU ms − terrain only's) against the speed of light's.
void printRatios() {
  const auto& f = figures();
  auto mean = [&](int c) {
    return f.count(c) && f.at(c).iterations ? f.at(c).ms / static_cast<double>(f.at(c).iterations) : -1.0;
  };
  const double terrain = mean(kTerrain), sol = mean(kSpeedOfLight);
  if (terrain < 0.0) return;
  std::printf("\n%-26s %10s %12s %14s %10s %12s\n", "case", "GPU ms", "veg. ms", "x speed of light", "blades",
              "M blades/s");
  // The wind cases' plants against terrain + simulation (the expansion's own cost with wind);
  // terrain + simulation against the terrain alone (the simulation's cost).
  const double windBase = mean(kTerrainWind) >= 0.0 ? mean(kTerrainWind) : terrain;
  for (const auto& [c, fig] : f) {
    const double ms = mean(c), veg = ms - (windy(static_cast<Case>(c)) && c != kTerrainWind ? windBase : terrain);
    const double ratio = sol > terrain && c != kTerrain ? veg / (sol - terrain) : 0.0;
    const double rate = veg > 0.0 && c != kTerrain ? static_cast<double>(fig.plants) / veg / 1000.0 : 0.0;
    std::printf("%-26s %10.3f %12.3f %14.2f %10llu %12.2f\n", kCaseNames[c], ms, c == kTerrain ? 0.0 : veg, ratio,
                static_cast<unsigned long long>(fig.plants), rate);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  printRatios();
  return 0;
}
