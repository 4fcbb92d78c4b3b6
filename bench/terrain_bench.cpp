// Grid-mesh construction over a synthetic DEM the size of the Zion sample (465 × 457): the
// CPU cost of turning heights into a drawable mesh in the local ENU frame.

#include <cmath>

#include <benchmark/benchmark.h>

#include "terrain/grid_mesh.h"

namespace {

vegstream::terrain::HeightGrid makeGrid(int w, int h) {
  vegstream::terrain::HeightGrid g;
  g.width = w;
  g.height = h;
  g.lonFirst = -113.24;
  g.latFirst = 37.51;
  g.lonStep = 1.0 / 1200.0;
  g.latStep = -1.0 / 1200.0;
  g.heights.resize(static_cast<size_t>(w) * static_cast<size_t>(h));
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      g.heights[static_cast<size_t>(r * w + c)] = static_cast<float>(1500.0 + 400.0 * std::sin(c * 0.05) * std::cos(r * 0.04));
  return g;
}

void BM_BuildGridMesh(benchmark::State& state) {
  const auto grid = makeGrid(465, 457);
  const vegstream::geo::LocalFrame frame({grid.centreLat(), grid.centreLon(), 0.0});
  const int step = static_cast<int>(state.range(0));
  size_t triangles = 0;
  for (auto _ : state) {
    auto mesh = vegstream::terrain::buildGridMesh(grid, frame, {step});
    triangles = mesh.triangleCount();
    benchmark::DoNotOptimize(mesh.indices.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["tris/s"] = benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_BuildGridMesh)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

}  // namespace
