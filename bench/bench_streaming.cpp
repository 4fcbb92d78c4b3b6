// Tile streaming throughput on the Zion sample (imported once, zoom ≤ 12, JPEG imagery):
//   BM_DecodeHeightPng / BM_DecodeImageryJpeg — one thread decoding one tile's bytes from memory
//     (tiles/s per core: what a decode worker sustains);
//   BM_StreamerSettle — a fresh TileStreamer over LocalTileSource loading every tile of the
//     dataset (heights + imagery, all zooms) until resident: I/O threads + decode threads.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include <benchmark/benchmark.h>
#include <unistd.h>

#include "datasets/geotiff_import.h"
#include "datasets/progress.h"
#include "datasets/tile_codec.h"
#include "streaming/local_tile_source.h"
#include "streaming/tile_streamer.h"

namespace {
namespace fs = std::filesystem;
using namespace vegstream;
using streaming::TileKey;
using streaming::TileLayer;

struct Zion {
  fs::path dir;
  datasets::DatasetMeta meta;
  std::vector<TileKey> keys;  // every tile file of the dataset
  bool ok = false;

  Zion() {
    dir = fs::temp_directory_path() / ("vegstream_bench_streaming_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const fs::path zion = fs::path(VEGSTREAM_DATASETS_DIR) / "zion";
    datasets::GeoTiffImportOptions o;
    o.dem = {(zion / "srtm.tif").string()};
    o.imagery.bands = {(zion / "landsat_b4.tif").string(), (zion / "landsat_b3.tif").string(),
                      (zion / "landsat_b2.tif").string()};
    o.imagery.radiometry.method = datasets::RadiometryMethod::Reflectance;  // as the demo imports it
    o.imageryDatetime = "2015-08-18T17:58:00Z";
    o.maxZoom = 12;
    o.out = dir;
    datasets::NullProgress progress;
    auto m = datasets::importGeoTiff(o, makeNullLogger(), progress);
    if (!m) {
      std::fprintf(stderr, "bench_streaming: cannot import the Zion sample: %s\n", m.error().message.c_str());
      return;
    }
    meta = *m;
    for (int z = meta.minZoom; z <= meta.maxZoom; ++z)
      for (const auto& id : geo::tilesCovering(meta.bounds, z))
        for (auto layer : {TileLayer::Height, TileLayer::Imagery}) {
          const TileKey k{layer, id};
          if (fs::exists(dir / streaming::datasetRelativePath(k, meta))) keys.push_back(k);
        }
    ok = true;
  }
  ~Zion() { fs::remove_all(dir); }

  // The largest file of the layer at the finest zoom: a tile full of data (edge tiles are
  // mostly nodata and decode faster than is typical).
  std::vector<uint8_t> bytesOfLargest(TileLayer layer) const {
    fs::path best;
    uintmax_t bestSize = 0;
    for (const auto& k : keys) {
      const fs::path p = dir / streaming::datasetRelativePath(k, meta);
      if (k.layer == layer && k.id.z == meta.maxZoom && fs::file_size(p) > bestSize) {
        best = p;
        bestSize = fs::file_size(p);
      }
    }
    std::ifstream in(best, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
};

const Zion& zion() {
  static const Zion z;
  return z;
}

void BM_DecodeHeightPng(benchmark::State& state) {
  if (!zion().ok) return state.SkipWithError("no Zion dataset");
  const auto bytes = zion().bytesOfLargest(TileLayer::Height);
  for (auto _ : state) {
    auto t = datasets::decodeHeightTile(bytes, {}, zion().meta.elevationEncoding, datasets::kTileSize, "bench");
    if (!t) return state.SkipWithError(t.error().message.c_str());
    benchmark::DoNotOptimize(t->heights.data());
  }
  state.counters["tiles/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["file_bytes"] = double(bytes.size());
}
BENCHMARK(BM_DecodeHeightPng)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DecodeImageryJpeg(benchmark::State& state) {
  if (!zion().ok) return state.SkipWithError("no Zion dataset");
  const auto bytes = zion().bytesOfLargest(TileLayer::Imagery);
  for (auto _ : state) {
    auto t = datasets::decodeColorTile(bytes, {}, datasets::kTileSize, "bench");
    if (!t) return state.SkipWithError(t.error().message.c_str());
    benchmark::DoNotOptimize(t->rgba.data());
  }
  state.counters["tiles/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["file_bytes"] = double(bytes.size());
}
BENCHMARK(BM_DecodeImageryJpeg)->Unit(benchmark::kMillisecond)->UseRealTime();

// Argument: decode threads.
void BM_StreamerSettle(benchmark::State& state) {
  if (!zion().ok) return state.SkipWithError("no Zion dataset");
  std::vector<streaming::TileWant> wants;
  for (size_t i = 0; i < zion().keys.size(); ++i) wants.push_back({zion().keys[i], double(i), false});
  for (auto _ : state) {
    streaming::StreamingOptions o;
    o.decodeThreads = int(state.range(0));
    auto source = std::make_shared<streaming::LocalTileSource>(zion().dir);
    streaming::TileStreamer s(source, zion().meta, o, makeNullLogger());
    s.settle(wants, 0.0);
    if (s.frameStats().wantedResident != wants.size()) return state.SkipWithError("not every tile became resident");
  }
  state.counters["tiles"] = double(wants.size());
  state.counters["tiles/s"] = benchmark::Counter(double(wants.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_StreamerSettle)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
