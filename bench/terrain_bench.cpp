// Grid-mesh construction over a synthetic DEM the size of the Zion sample (465 × 457): the
// CPU cost of turning heights into a drawable mesh in the local ENU frame. Chunked-LOD tile
// selection over the Zion sample's bounds (tiles of zoom 8 … 14, nodes to 17) for a low 1920 × 1080 camera, and the
// wedgie table of one height tile (ROAM's error bounds, built on a decode thread).

#include <cmath>

#include <benchmark/benchmark.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include "terrain/grid_mesh.h"
#include "terrain/tile_selection.h"
#include "terrain/wedgie_table.h"

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
      g.heights[static_cast<size_t>(r * w + c)] =
          static_cast<float>(1500.0 + 400.0 * std::sin(c * 0.05) * std::cos(r * 0.04));
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
  state.counters["tris/s"] =
      benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_BuildGridMesh)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

// The Zion import's dataset.json (tests/datasets/import/import_zion_test.cpp, --max-zoom 14),
// nodes down to one quad per data pixel.
vegstream::terrain::SelectionDataset zionDataset() {
  return {{-113.23958, 37.13208, -112.85208, 37.51292}, 8, 14 + vegstream::terrain::kLevelsBeyondData, 1024.3, 2892.0};
}

// 150 m above the highest point near the south-west corner, looking north-east 10° down, or a
// top-down view of the whole dataset from 80 km (range(0) = 0 / 1); range(1): maxNodes.
void BM_SelectTiles(benchmark::State& state) {
  using namespace vegstream;
  const terrain::SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = geo::frameAtCentre(d.bounds, 0.5 * (d.minHeightM + d.maxHeightM));
  const double fov = 60.0 * 3.14159265358979 / 180.0;
  const bool low = state.range(0) == 0;
  const glm::dvec3 eye = low ? frame.toLocal({d.bounds.southDeg + 0.05, d.bounds.westDeg + 0.05, d.maxHeightM + 150.0})
                             : frame.toLocal({d.bounds.centre().y, d.bounds.centre().x, 80'000.0});
  const glm::dvec3 dir = low ? glm::normalize(glm::dvec3(1.0, 1.0, -0.25)) : glm::dvec3(0, 0, -1);
  const glm::dmat4 vp = glm::perspective(fov, 1920.0 / 1080.0, 1.0, 1e6) *
                        glm::lookAt(eye, eye + dir, low ? glm::dvec3(0, 0, 1) : glm::dvec3(0, 1, 0));
  const terrain::SelectionView view{eye, vp, 1080.0, fov};
  const terrain::SelectionOptions options{2.0, static_cast<int>(state.range(1))};
  terrain::Selection s;
  // range(2) = 1: with the nodes' boxes kept from one selection to the next (as StreamedTerrain
  // keeps them from frame to frame); the first selection fills the memo.
  terrain::NodeBoxes memo;
  terrain::NodeBoxes* kept = state.range(2) != 0 ? &memo : nullptr;
  for (auto _ : state) {
    s = terrain::selectTiles(view, d, frame, options, {}, kept);
    benchmark::DoNotOptimize(s.nodes.data());
  }
  state.counters["nodes"] = static_cast<double>(s.nodes.size());
  state.counters["errorPx"] = s.achievedErrorPx;
  state.counters["limited"] = s.budgetLimited ? 1.0 : 0.0;
}
BENCHMARK(BM_SelectTiles)
    ->Args({0, 512, 0})
    ->Args({0, 512, 1})
    ->Args({0, 100'000, 0})
    ->Args({0, 100'000, 1})
    ->Args({1, 512, 0})
    ->Args({1, 512, 1})
    ->Unit(benchmark::kMicrosecond);

// The wedgie table of one synthetic tile (what each height tile costs a decode thread).
void BM_WedgieTable(benchmark::State& state) {
  using namespace vegstream;
  datasets::HeightTile tile;
  tile.id = {14, 3100, 6300};
  tile.heights.resize(static_cast<size_t>(tile.size) * static_cast<size_t>(tile.size));
  for (int y = 0; y < tile.size; ++y)
    for (int x = 0; x < tile.size; ++x)
      tile.heights[static_cast<size_t>(y * tile.size + x)] =
          static_cast<float>(1500.0 + 400.0 * std::sin(x * 0.05) * std::cos(y * 0.04));
  for (auto _ : state) {
    terrain::WedgieTable t(tile, 8);
    benchmark::DoNotOptimize(&t);
  }
}
BENCHMARK(BM_WedgieTable)->Unit(benchmark::kMillisecond);

}  // namespace
