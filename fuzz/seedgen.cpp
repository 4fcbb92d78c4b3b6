// fuzz_seedgen OUT_DIR: small valid inputs for every fuzz target, written by the project's own
// writers (tiles of 32 pixels, a dataset.json, tiny GeoTIFFs) into OUT_DIR/<target>/. Run by
// scripts/fuzz at fuzz time; its output at the time of writing is also committed as
// fuzz/corpus/ (each file a few KB), which the GCC regression test runs.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "datasets/canopy.h"
#include "datasets/dataset_format.h"
#include "datasets/landcover.h"
#include "datasets/tile_codec.h"
#include "flight/record_table.h"
#include "flight/summary.h"
#include "tests/datasets/tiny_tiff.h"

namespace fs = std::filesystem;
using namespace vegstream;

namespace {

constexpr int kSide = 32;
fs::path out;

std::vector<uint8_t> bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put(const std::string& target, const std::string& name, const std::vector<uint8_t>& bytes) {
  fs::create_directories(out / target);
  std::ofstream(out / target / name, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::vector<uint8_t> cat(std::initializer_list<std::vector<uint8_t>> parts) {
  std::vector<uint8_t> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

std::vector<uint8_t> text(const std::string& s) { return {s.begin(), s.end()}; }

void check(const Status& s) {
  if (!s) {
    std::fprintf(stderr, "fuzz_seedgen: %s\n", s.error().message.c_str());
    std::exit(1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seedgen OUT_DIR\n");
    return 2;
  }
  out = argv[1];
  const fs::path tmp = out / ".tmp";
  fs::create_directories(tmp);

  datasets::HeightTile heights;
  datasets::ColorTile colours;
  datasets::LandcoverTile landcover;
  datasets::CanopyTile canopy;
  heights.size = colours.size = landcover.size = canopy.size = kSide;
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      // A ridge and a valley, coloured by height: forest low, rock high.
      const double h = 1500.0 + 400.0 * std::sin(x * 0.2) * std::cos(y * 0.15) + 3.0 * x;
      heights.heights.push_back(static_cast<float>(h));
      const auto shade = static_cast<uint8_t>(std::clamp((h - 1000.0) / 8.0, 0.0, 255.0));
      colours.rgba.insert(colours.rgba.end(), {shade, static_cast<uint8_t>(90 + shade / 3), 60, 255});
      colours.ndvi.push_back(static_cast<uint8_t>(40 + (x * 7 + y * 3) % 200));
      landcover.classes.push_back(static_cast<uint8_t>(x + y < 4 ? 0 : 10 + 10 * ((x / 8 + y / 8) % 9)));
      canopy.decimetres.push_back(x == y ? datasets::kNoCanopy : static_cast<uint16_t>((x * 37 + y * 11) % 400));
    }
  }
  heights.heights[5] = NAN;

  check(datasets::writeHeightTile(tmp / "terrarium.png", heights, datasets::ElevationEncoding::Terrarium));
  check(datasets::writeHeightTile(tmp / "terrain-rgb.png", heights, datasets::ElevationEncoding::TerrainRgb));
  check(datasets::writeColorTile(tmp / "imagery.png", colours, datasets::ImageryFormat::Png));
  check(datasets::writeColorTile(tmp / "imagery.jpg", colours, datasets::ImageryFormat::Jpeg, 80));
  check(datasets::writeNdviTile(tmp / "ndvi.png", colours));
  check(datasets::writeLandcoverTile(tmp / "landcover.png", landcover));
  check(datasets::writeCanopyTile(tmp / "canopy.png", canopy));
  const auto terrarium = bytesOf(tmp / "terrarium.png"), terrainRgb = bytesOf(tmp / "terrain-rgb.png");
  const auto png = bytesOf(tmp / "imagery.png"), jpeg = bytesOf(tmp / "imagery.jpg");
  const auto ndvi = bytesOf(tmp / "ndvi.png"), classes = bytesOf(tmp / "landcover.png");
  const auto chm = bytesOf(tmp / "canopy.png");

  put("elevation_tile", "terrarium.png", terrarium);
  put("elevation_tile", "terrain-rgb.png", terrainRgb);
  put("imagery_tile", "imagery.png", png);
  put("imagery_tile", "imagery.jpg", jpeg);
  put("imagery_tile", "ndvi-grey.png", ndvi);

  // dataset.json: a full one (every optional layer) and a plain one.
  datasets::DatasetMeta meta;
  meta.name = "seed";
  meta.bounds = {7.9, 46.5, 8.0, 46.6};
  meta.minZoom = 9;
  meta.maxZoom = 13;
  meta.minHeightM = 612.5;
  meta.maxHeightM = 2890.25;
  meta.imagery = datasets::ImageryFormat::Png;
  meta.imageryDatetime = "2015-08-18T17:59:00Z";
  meta.tileSize = kSide;
  meta.attribution = "synthetic";
  meta.sources = {{"elevation", "seed 7", "WGS 84 (EPSG:4326)", "fractal relief"},
                  {"imagery", "seed 7", "WGS 84 (EPSG:4326)", "biome colours"}};
  meta.elevationTiles = 40;
  meta.imageryTiles = 40;
  meta.ndvi = true;
  meta.ndviTiles = 40;
  meta.landcover = datasets::LandcoverScheme::Nlcd;
  meta.landcoverTiles = 12;
  meta.canopyZoom = 13;
  meta.canopyTiles = 3;
  meta.bytes = 123456;
  check(datasets::writeDatasetMeta(tmp, meta));
  const auto full = bytesOf(tmp / "dataset.json");
  datasets::DatasetMeta plain = meta;
  plain.imagery = datasets::ImageryFormat::Jpeg;
  plain.elevationEncoding = datasets::ElevationEncoding::TerrainRgb;
  plain.ndvi = false;
  plain.ndviTiles = 0;
  plain.landcover.reset();
  plain.canopyZoom.reset();
  plain.landcoverTiles = plain.canopyTiles = 0;
  plain.imageryDatetime.clear();
  check(datasets::writeDatasetMeta(tmp, plain));
  const auto jpegMeta = bytesOf(tmp / "dataset.json");
  put("dataset_json", "full.json", full);
  put("dataset_json", "plain.json", jpegMeta);

  // tile_contract: dataset.json, NUL, the layer byte, the tile.
  const std::vector<uint8_t> nul = {0};
  put("tile_contract", "elevation", cat({full, nul, {0}, terrarium}));
  put("tile_contract", "elevation-terrain-rgb", cat({jpegMeta, nul, {0}, terrainRgb}));
  put("tile_contract", "imagery-png", cat({full, nul, {1}, png}));
  put("tile_contract", "imagery-jpeg", cat({jpegMeta, nul, {1}, jpeg}));
  put("tile_contract", "ndvi", cat({full, nul, {2}, ndvi}));
  put("tile_contract", "landcover", cat({full, nul, {3}, classes}));
  put("tile_contract", "canopy", cat({full, nul, {4}, chm}));

  // http_response: content type, status, path/flags (http_response.cpp), then the body.
  put("http_response", "elevation-200", cat({{1, 0, 0}, terrarium}));
  put("http_response", "elevation-terrain-rgb-200", cat({{1, 0, 8}, terrainRgb}));
  put("http_response", "imagery-jpeg-200", cat({{2, 0, 1}, jpeg}));
  put("http_response", "imagery-png-unannounced", cat({{0, 0, 0x12}, png}));
  put("http_response", "ndvi-200", cat({{1, 0, 3}, ndvi}));
  put("http_response", "landcover-200", cat({{1, 0, 4}, classes}));
  put("http_response", "canopy-200", cat({{1, 0, 5}, chm}));
  put("http_response", "html-error-page", cat({{5, 0, 0}, text("<html><body>502 Bad Gateway</body></html>")}));
  put("http_response", "redirect", cat({{0, 6, 0}, text("https://tiles.example.org:8443/zion/elevation/12/1/2.png")}));
  put("http_response", "redirect-elsewhere", cat({{0, 7, 8}, text("http://cdn.example.net/a/b.png?x=1#f")}));
  put("http_response", "raw-content-type", cat({{0xe0 + 9, 0, 0}, text("image/png"), terrarium}));
  put("http_response", "dataset-json", cat({{7, 0, 0x46}, full}));

  // raster_source: tiny GeoTIFFs (tests/datasets/tiny_tiff.h) — UInt16 heights in WGS 84, Float32
  // with nodata, 8-bit RGB.
  namespace tt = datasets::test;
  const auto wgs84 = [] {
    return std::vector<tt::TinyTag>{
        tt::doubles(33550, {10, 10, 0}), tt::doubles(33922, {0, 0, 0, 100, 50, 0}),
        tt::shorts(34735, {1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326})};
  };
  tt::TinyImage u16;
  u16.pixels = tt::pixelBytes(std::vector<uint16_t>{1, 2, 3, 4});
  u16.extra = wgs84();
  tt::writeTinyTiff(tmp / "u16.tif", u16);
  put("raster_source", "uint16-wgs84.tif", bytesOf(tmp / "u16.tif"));
  tt::TinyImage f32;
  f32.width = f32.height = 3;
  f32.bits = 32;
  f32.sampleFormat = 3;
  f32.pixels = tt::pixelBytes(std::vector<float>{1.5f, 2, 3, -9999, 5, 6, 7, 8, 9.25f});
  f32.extra = wgs84();
  f32.extra.push_back(tt::ascii(42113, "-9999"));
  tt::writeTinyTiff(tmp / "f32.tif", f32);
  put("raster_source", "float32-nodata.tif", bytesOf(tmp / "f32.tif"));
  tt::TinyImage rgb;
  rgb.width = rgb.height = 2;
  rgb.channels = 3;
  rgb.bits = 8;
  rgb.pixels = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120};
  rgb.extra = wgs84();
  tt::writeTinyTiff(tmp / "rgb.tif", rgb);
  put("raster_source", "rgb8-wgs84.tif", bytesOf(tmp / "rgb.tif"));

  // The JSON readers: a flight path with every section, a recording.json and the summary.json
  // made from it (the frames of fuzz/targets/json_readers.cpp).
  put("flight_path", "every-section.json", text(R"({
  "name": "seed",
  "description": "three keyframes, a capsule and a wind section",
  "keyframes": [
    {"t": 0, "lat": 46.55, "lon": 7.95, "alt_m": 500, "heading": 10, "pitch": -20},
    {"t": 5, "lat": 46.56, "lon": 7.96, "alt_m": 1800, "alt_ref": "msl", "heading": 20, "pitch": -10},
    {"t": 9.5, "lat": 46.57, "lon": 7.97, "alt_m": 30, "alt_ref": "terrain", "heading": 350, "pitch": 0}
  ],
  "colliders": [
    {"name": "log", "shape": "capsule", "radius_m": 0.5, "length_m": 4,
     "keyframes": [{"t": 0, "lat": 46.55, "lon": 7.95, "alt_m": 1}, {"t": 9, "lat": 46.551, "lon": 7.951, "alt_m": 1}]}
  ],
  "wind": {"speed_mps": 6, "direction_deg": 250, "gustiness": 0.6,
    "sources": [{"name": "fan", "type": "fan", "radius_m": 8, "strength_mps": 14, "direction_deg": 90,
                 "keyframes": [{"t": 0, "lat": 46.55, "lon": 7.95, "alt_m": 3, "alt_ref": "msl"}]}]}
}
)"));
  const std::string recording = R"({"path": "benchmark-30s", "fps": 60, "size": [640, 360], "msaa": 4,
  "device": {"name": "llvmpipe", "type": "cpu"}, "peak_rss_bytes": 123456789, "per_pass_gpu_times_meaningful": false}
)";
  put("recording_json", "recording.json", text(recording));
  const auto frames = flight::RecordTable::parseCsv(
      "frame,t_s,cpu_frame_ms,gpu_frame_ms,wall_ms,recorder_ms,terrain_triangles\n"
      "0,0,1.5,2.5,4,0.01,1000\n1,0.016667,1.25,40,42,0.01,1100\n2,0.033333,1.5,2.75,4.5,0.01,900\n",
      "seed/frames.csv");
  if (!frames) return 1;
  const auto summary = flight::makeSummaryJson(recording, "seed/recording.json", *frames);
  if (!summary) return 1;
  put("summary_json", "summary.json", text(*summary));

  fs::remove_all(tmp);
  return 0;
}
