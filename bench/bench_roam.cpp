// ROAM on real flights, rendering off (the CPU work does not depend on it): the bundled
// benchmark-30s and canyon-run paths over the Zion sample (heights imported once, max zoom 12),
// flown at 60 Hz with a 1920 × 1080 camera, error bound 2 px (and 4 px on benchmark-30s). Each frame: the tile selection's wants, the
// streamer settled (untimed: I/O is not the terrain's), then timed — the streamed terrain's
// pieces(): residency changes resampled, ROAM update (priorities, split/merge queues), output
// (hierarchical culling, drawn leaves per piece, seed triangles). Counters: per-frame ms
// (median, p99, max), ROAM update and output medians, drawn triangles (median), seed triangles,
// and the drawn triangles against a full-resolution grid of the same area (every selected tile
// drawn with 2 triangles per max-zoom pixel) as a ratio.

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define VEGSTREAM_BENCH_HAS_CALLGRIND 1
#endif
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "core/stopwatch.h"
#include "core/task_runner.h"
#include "datasets/dataset_format.h"
#include "datasets/geotiff_import.h"
#include "datasets/progress.h"
#include "scene/camera_views.h"
#include "flight/flight_path_json.h"
#include "flight/path_sampler.h"
#include "streaming/dataset_snapshot.h"
#include "streaming/open_tile_source.h"
#include "terrain/snapshot_grid.h"
#include "terrain/streamed_terrain.h"

namespace {

using namespace vegstream;
namespace fs = std::filesystem;

struct Zion {
  fs::path dir;
  datasets::DatasetMeta meta;
  bool ok = false;
  bool owned = false;  // imported here (removed at exit), not given by VEGSTREAM_BENCH_DATASET
  Zion() {
    // An imported Zion dataset (bench/gpu-measure passes its --dataset: the GPU host has no
    // ../shared/datasets to import from); else the sample's heights imported once here.
    if (const char* given = std::getenv("VEGSTREAM_BENCH_DATASET")) {
      dir = given;
      auto m = datasets::readDatasetMeta(dir);
      if (!m) {
        std::fprintf(stderr, "bench_roam: VEGSTREAM_BENCH_DATASET: %s\n", m.error().message.c_str());
        return;
      }
      meta = *m;
      ok = true;
      return;
    }
    dir = fs::temp_directory_path() / ("vegstream_bench_roam_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    owned = true;
    datasets::GeoTiffImportOptions o;
    o.dem = {(fs::path(VEGSTREAM_DATASETS_DIR) / "zion" / "srtm.tif").string()};
    o.maxZoom = 12;
    o.out = dir;
    datasets::NullProgress progress;
    auto m = datasets::importGeoTiff(o, makeNullLogger(), progress);
    if (!m) {
      std::fprintf(stderr, "bench_roam: cannot import the Zion sample: %s\n", m.error().message.c_str());
      return;
    }
    meta = *m;
    ok = true;
  }
  ~Zion() {
    if (owned) fs::remove_all(dir);
  }
};

Zion& zion() {
  static Zion z;
  return z;
}

unsigned long long ull(uint64_t v) { return static_cast<unsigned long long>(v); }

// CPU time of the calling thread (ms): the frame's work without the time the scheduler gave
// other processes (on a shared machine a preempted frame is ~4 ms longer on the wall clock).
double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double x = p * static_cast<double>(v.size() - 1);
  const auto i = static_cast<size_t>(x);
  const double f = x - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

constexpr double kW = 1920.0, kH = 1080.0, kFps = 60.0;

Result<flight::FlightPath> bundledPath(const char* name) {
  // VEGSTREAM_SOURCE_DIR: this checkout; VEGSTREAM_BENCH_SOURCE_DIR overrides it (a copy elsewhere).
  const char* root = std::getenv("VEGSTREAM_BENCH_SOURCE_DIR");
  return flight::loadFlightPath(fs::path(root ? root : VEGSTREAM_SOURCE_DIR) / "flight" / "paths" /
                                (std::string(name) + ".json"));
}

// The streamed terrain of one flight over the Zion sample. settle(t): the tile selection's wants
// for the camera at t, the streamer settled (untimed: I/O is not the terrain's).
struct RoamFlight {
  std::shared_ptr<streaming::TileSource> source;
  terrain::HeightGrid grid;
  geo::LocalFrame frame;
  std::unique_ptr<streaming::TileStreamer> streamer;
  std::unique_ptr<terrain::StreamedTerrain> terrain;
  flight::PathSampler sampler;
  std::string error;  // set when it cannot fly

  RoamFlight(const Zion& z, const flight::FlightPath& path, const terrain::StreamedTerrainOptions& options)
      : frame({0.5 * (z.meta.bounds.southDeg + z.meta.bounds.northDeg), z.meta.bounds.centre().x, 0.0}),
        sampler(path) {
    auto opened = streaming::openTileSource(z.dir.string(), {});
    if (!opened) {
      error = "cannot open the dataset";
      return;
    }
    source = *opened;
    auto ground = streaming::loadGroundHeights(*source, z.meta, {});
    if (!ground) {
      error = "no ground heights";
      return;
    }
    grid = terrain::heightGridFrom(*ground);
    streamer = std::make_unique<streaming::TileStreamer>(source, z.meta, terrain::streamingOptionsFor(z.meta, {}),
                                                         makeNullLogger());
    terrain = std::make_unique<terrain::StreamedTerrain>(*streamer, frame, options);
  }
  int frames() const { return static_cast<int>(std::floor(sampler.duration() * kFps)) + 1; }
  void settle(double t) {
    const flight::GroundHeight groundFn = [&](double lat, double lon) { return grid.sampleLonLat(lon, lat); };
    const geo::Camera cam = scene::cameraFor(frame, sampler.sample(t, groundFn));
    auto wants = terrain->wants(scene::selectionViewFor(cam, kW, kH), scene::eyeViewFor(cam, kW, kH), {});
    for (int round = 0; round < 32; ++round) {
      streamer->settle(wants, t);
      auto again = terrain->wantsAgain();
      const bool same = again.size() == wants.size();
      wants = std::move(again);
      if (same) break;
    }
  }
};

void flyPath(benchmark::State& state, const char* pathName) {
  Zion& z = zion();
  if (!z.ok) return state.SkipWithError("no Zion dataset");
  auto path = bundledPath(pathName);
  if (!path) return state.SkipWithError(path.error().message.c_str());
  for (auto _ : state) {
    terrain::StreamedTerrainOptions to;
    to.maxErrorPx = static_cast<double>(state.range(0));
    // range(1) = 0: the same work done in full every frame (no deferred priorities, no cached
    // chunks), the baseline the incremental figures are a ratio to.
    to.roam.deferPriorities = to.roam.cacheChunks = state.range(1) != 0;
    // range(1) = 2: one worker beside the frame thread, as the app has its pool
    // (RoamOptions::tasks): the priority traversal's subtrees and the output's chunks are shared
    // with it, and compactions are copied on it. The copy overlaps the output and then the
    // untimed settle of the next frame, as in the app it overlaps the output, the seeding, the
    // record and the wait for the GPU; what it does not hide is the next update's compact_wait_ms.
    ThreadPool worker(1);
    if (state.range(1) == 2) to.roam.tasks = &worker;
    RoamFlight flight(z, *path, to);
    if (!flight.error.empty()) return state.SkipWithError(flight.error.c_str());
    terrain::StreamedTerrain& terrain = *flight.terrain;
    std::vector<double> frameMs, cpuMs, updateMs, outputMs, drawn, seeds, ratio, leaves, ops, morphing, visited,
        computed, reused, built, moved, emitted;
    const int frames = flight.frames();
    int compactions = 0;
    // VEGSTREAM_BENCH_CSV=DIR: one row per frame in DIR/<benchmark name>.csv (where the time goes).
    std::unique_ptr<FILE, int (*)(FILE*)> csv(nullptr, &std::fclose);
    if (const char* dir = std::getenv("VEGSTREAM_BENCH_CSV")) {
      const std::string name = std::string(pathName) + "_" + std::to_string(state.range(0)) + "px_" +
                               (state.range(1) == 2 ? "incremental-worker" : state.range(1) != 0 ? "incremental" : "every-frame");
      csv.reset(std::fopen((fs::path(dir) / (name + ".csv")).c_str(), "w"));
      if (!csv) return state.SkipWithError("VEGSTREAM_BENCH_CSV: cannot write there");
      std::fprintf(
          csv.get(),
          "frame,ms,cpu_ms,update_ms,compact_ms,compact_wait_ms,priorities_ms,split_ms,merge_ms,output_ms,leaves,splits,merges,"
          "visited,computed,chunks_reused,chunks_built,emitted,seeds,created,compacted\n");
    }
    // VEGSTREAM_BENCH_CALLGRIND=FIRST-LAST: under `valgrind --tool=callgrind --instr-atstart=no`,
    // only frames FIRST..LAST are instrumented, and the flight stops after them: instruction and
    // simulated cache-miss counts of a stretch of the flight (the descent: 130-199), the same on
    // every run, where this machine's wall clock moves by half between runs.
#ifdef VEGSTREAM_BENCH_HAS_CALLGRIND
    int profileFirst = -1, profileLast = -1;
    if (const char* range = std::getenv("VEGSTREAM_BENCH_CALLGRIND")) {
      if (std::sscanf(range, "%d-%d", &profileFirst, &profileLast) != 2 || profileFirst < 0 || profileLast < profileFirst)
        return state.SkipWithError("VEGSTREAM_BENCH_CALLGRIND: expected FIRST-LAST frames, e.g. 130-199");
    }
#else
    if (std::getenv("VEGSTREAM_BENCH_CALLGRIND"))
      return state.SkipWithError("VEGSTREAM_BENCH_CALLGRIND: built without valgrind/callgrind.h (apt install valgrind)");
#endif
    for (int i = 0; i < frames; ++i) {
      const double t = i / kFps;
      flight.settle(t);
#ifdef VEGSTREAM_BENCH_HAS_CALLGRIND
      if (i == profileFirst) CALLGRIND_START_INSTRUMENTATION;
      if (profileLast >= 0 && i == profileLast + 1) {
        CALLGRIND_STOP_INSTRUMENTATION;
        break;
      }
#endif
      Stopwatch watch;
      const double cpu0 = threadCpuMs();
      const auto pieces = terrain.pieces(t);
      frameMs.push_back(watch.elapsedMs());
      cpuMs.push_back(threadCpuMs() - cpu0);
      const terrain::TerrainFrameFigures& f = terrain.figures();
      updateMs.push_back(f.roam.updateMs);
      outputMs.push_back(f.roam.outputMs);
      drawn.push_back(static_cast<double>(f.triangles));
      leaves.push_back(static_cast<double>(f.roam.leaves));
      seeds.push_back(static_cast<double>(f.roam.seedTriangles));
      ops.push_back(static_cast<double>(f.roam.splits + f.roam.merges + f.roam.mergesStarted));
      morphing.push_back(static_cast<double>(f.roam.morphingVertices));
      visited.push_back(static_cast<double>(f.roam.nodesVisited));
      computed.push_back(static_cast<double>(f.roam.prioritiesComputed));
      reused.push_back(static_cast<double>(f.roam.chunksReused));
      built.push_back(static_cast<double>(f.roam.chunksBuilt));
      moved.push_back(static_cast<double>(f.roam.chunksMoved));
      emitted.push_back(static_cast<double>(f.roam.leavesEmitted));
      double gridTriangles = 0.0;
      for (const terrain::TerrainPiece& p : pieces)
        if (p.mesh && p.node.z <= z.meta.maxZoom)
          gridTriangles += 2.0 * std::pow(256.0 * std::ldexp(1.0, z.meta.maxZoom - p.node.z), 2.0);
      if (gridTriangles > 0.0) ratio.push_back(static_cast<double>(f.triangles) / gridTriangles);
      if (csv)
        std::fprintf(
            csv.get(),
            "%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%d\n", i,
            frameMs.back(), cpuMs.back(), f.roam.updateMs, f.roam.compactMs, f.roam.compactWaitMs, f.roam.prioritiesMs, f.roam.splitMs,
            f.roam.mergeMs, f.roam.outputMs, ull(f.roam.leaves), ull(f.roam.splits), ull(f.roam.merges),
            ull(f.roam.nodesVisited), ull(f.roam.prioritiesComputed), ull(f.roam.chunksReused), ull(f.roam.chunksBuilt),
            ull(f.roam.leavesEmitted), ull(f.roam.seedTriangles), ull(f.roam.leavesCreated), f.roam.compacted ? 1 : 0);
      compactions += f.roam.compacted ? 1 : 0;
    }
    state.counters["frames"] = static_cast<double>(frames);
    state.counters["ms_p50"] = percentile(frameMs, 0.5);
    state.counters["ms_p99"] = percentile(frameMs, 0.99);
    state.counters["ms_max"] = percentile(frameMs, 1.0);
    state.counters["cpu_ms_p50"] = percentile(cpuMs, 0.5);
    state.counters["cpu_ms_p99"] = percentile(cpuMs, 0.99);
    state.counters["cpu_ms_max"] = percentile(cpuMs, 1.0);
    state.counters["over_4ms"] =
        static_cast<double>(std::count_if(frameMs.begin(), frameMs.end(), [](double ms) { return ms > 4.0; }));
    state.counters["compactions"] = compactions;
    state.counters["update_ms_p50"] = percentile(updateMs, 0.5);
    state.counters["output_ms_p50"] = percentile(outputMs, 0.5);
    state.counters["tris_p50"] = percentile(drawn, 0.5);
    state.counters["leaves_p50"] = percentile(leaves, 0.5);
    state.counters["ops_p50"] = percentile(ops, 0.5);
    state.counters["morphing_p50"] = percentile(morphing, 0.5);
    state.counters["visited_p50"] = percentile(visited, 0.5);
    state.counters["computed_p50"] = percentile(computed, 0.5);
    state.counters["chunks_reused_p50"] = percentile(reused, 0.5);
    state.counters["chunks_built_p50"] = percentile(built, 0.5);
    state.counters["chunks_moved_p50"] = percentile(moved, 0.5);
    state.counters["emitted_p50"] = percentile(emitted, 0.5);
    state.counters["emitted_p99"] = percentile(emitted, 0.99);
    state.counters["seed_tris_p50"] = percentile(seeds, 0.5);
    state.counters["vs_full_grid_p50"] = percentile(ratio, 0.5);
  }
}

// A compaction's copy (RoamMesh::buildCompaction) of the mesh benchmark-30s has at 20 s (80 k
// leaves, at 15 m over the Kolob plateau), its pools scattered by the flight since the last
// compaction: on the calling thread alone (range(0) = 1) or with range(0) − 1 workers helping,
// the subtrees split between them (roam_mesh_compaction.cpp). Each iteration copies the
// scattered mesh first, untimed. Counters: leaves, and the pairs allocated since the last
// compaction against those live (how scattered the pools are).
void BM_RoamCompaction(benchmark::State& state) {
  Zion& z = zion();
  if (!z.ok) return state.SkipWithError("no Zion dataset");
  auto path = bundledPath("benchmark-30s");
  if (!path) return state.SkipWithError(path.error().message.c_str());
  RoamFlight flight(z, *path, {});
  if (!flight.error.empty()) return state.SkipWithError(flight.error.c_str());
  for (int i = 0; i <= static_cast<int>(20.0 * kFps); ++i) {
    flight.settle(i / kFps);
    (void)flight.terrain->pieces(i / kFps);
  }
  const terrain::RoamMesh& scattered = flight.terrain->roam().mesh();
  const auto threads = static_cast<int>(state.range(0));
  std::unique_ptr<ThreadPool> pool = threads > 1 ? std::make_unique<ThreadPool>(threads - 1) : nullptr;
  for (auto _ : state) {
    terrain::RoamMesh mesh = scattered;
    terrain::RoamCompaction c = mesh.beginCompaction();
    // The pools as the app's kept spare ones are: every page touched already.
    c.nodes.resize(c.nodes.capacity());
    c.vertices.resize(c.vertices.capacity());
    Stopwatch watch;
    mesh.buildCompaction(c, pool.get());
    state.SetIterationTime(watch.elapsedMs() * 1e-3);
    (void)mesh.endCompaction(std::move(c));
  }
  state.counters["leaves"] = static_cast<double>(scattered.leafCount());
  state.counters["churn"] =
      static_cast<double>(scattered.pairsAllocatedSinceCompact()) / static_cast<double>(scattered.livePairs());
}

void BM_RoamBenchmark30s(benchmark::State& state) { flyPath(state, "benchmark-30s"); }
void BM_RoamCanyonRun(benchmark::State& state) { flyPath(state, "canyon-run"); }
// range(0): the screen-space error bound, pixels; range(1): incremental with compactions on a
// worker (2, the app's), incremental on the frame thread alone (1), or everything every frame (0).
BENCHMARK(BM_RoamBenchmark30s)
    ->Args({2, 2})
    ->Args({2, 1})
    ->Args({2, 0})
    ->Args({4, 2})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_RoamCompaction)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond)->UseManualTime();
BENCHMARK(BM_RoamCanyonRun)->Args({2, 2})->Args({2, 1})->Args({2, 0})->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
