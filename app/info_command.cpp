// `vegstream info` (info_command.h). Counts come from dataset.json and, per zoom, from the
// files actually present, so a dataset damaged after its import shows the difference.

#include "app/info_command.h"

#include <iostream>
#include <map>
#include <set>
#include <system_error>

#include <nlohmann/json.hpp>

#include "app/exit_codes.h"
#include "datasets/dataset_reader.h"
#include "datasets/tilejson.h"
#include "geo/crs.h"

namespace vegstream::app {
namespace fs = std::filesystem;

namespace {

struct ZoomCounts {
  uint64_t elevation = 0, imagery = 0, ndvi = 0, landcover = 0, canopy = 0, bytes = 0;
};

// Tiles on disk under DIR/{elevation,imagery,ndvi,landcover,canopy}/{z}/{x}/{y}.ext, per zoom.
std::map<int, ZoomCounts> countTiles(const fs::path& dir) {
  std::map<int, ZoomCounts> zooms;
  for (const char* kind : {"elevation", "imagery", "ndvi", "landcover", "canopy"}) {
    std::error_code ec;
    const fs::path root = dir / kind;
    if (!fs::is_directory(root, ec)) continue;
    for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
      if (it.depth() != 2 || !it->is_regular_file(ec)) continue;
      const std::string zText = it->path().parent_path().parent_path().filename().string();
      if (zText.empty() || zText.find_first_not_of("0123456789") != std::string::npos || zText.size() > 2) continue;
      ZoomCounts& c = zooms[std::stoi(zText)];
      (kind[0] == 'e'   ? c.elevation
       : kind[0] == 'i' ? c.imagery
       : kind[0] == 'n' ? c.ndvi
       : kind[0] == 'c' ? c.canopy
                        : c.landcover) += 1;
      const auto size = it->file_size(ec);
      if (!ec) c.bytes += size;
    }
  }
  return zooms;
}

// Every zoom's counts as JSON (the layers the dataset has), and their sum into total.
nlohmann::json perZoomJson(const std::map<int, ZoomCounts>& zooms, const datasets::DatasetMeta& m, ZoomCounts& total) {
  nlohmann::json perZoom = nlohmann::json::array();
  for (const auto& [z, c] : zooms) {
    nlohmann::json zoom = {{"zoom", z}, {"elevation", c.elevation}, {"imagery", c.imagery}, {"bytes", c.bytes}};
    if (m.ndvi) zoom["ndvi"] = c.ndvi;
    if (m.landcover) zoom["landcover"] = c.landcover;
    if (m.canopyZoom) zoom["canopy"] = c.canopy;
    perZoom.push_back(zoom);
    total.elevation += c.elevation;
    total.imagery += c.imagery;
    total.ndvi += c.ndvi;
    total.landcover += c.landcover;
    total.canopy += c.canopy;
    total.bytes += c.bytes;
  }
  return perZoom;
}

// A warning for each layer whose tiles on disk are not what dataset.json counts.
void warnMismatches(const std::string& dataset, const datasets::DatasetMeta& m, const ZoomCounts& onDisk,
                    const Logger& log) {
  if (onDisk.elevation != m.elevationTiles || onDisk.imagery != m.imageryTiles)
    log->warn("{}: dataset.json counts {} elevation and {} imagery tiles, the directory holds {} and {}", dataset,
              m.elevationTiles, m.imageryTiles, onDisk.elevation, onDisk.imagery);
  if (onDisk.ndvi != m.ndviTiles)
    log->warn("{}: dataset.json counts {} NDVI tiles, the directory holds {}", dataset, m.ndviTiles, onDisk.ndvi);
  if (onDisk.landcover != m.landcoverTiles)
    log->warn("{}: dataset.json counts {} landcover tiles, the directory holds {}", dataset, m.landcoverTiles,
              onDisk.landcover);
  if (m.canopyZoom && onDisk.canopy != m.canopyTiles)
    log->warn("{}: dataset.json counts {} canopy tiles, the directory holds {}", dataset, m.canopyTiles,
              onDisk.canopy);
}

// "tiles": dataset.json's counts, per zoom and on disk.
nlohmann::json tilesJson(const datasets::DatasetMeta& m, const nlohmann::json& perZoom, const ZoomCounts& onDisk) {
  nlohmann::json tiles = {{"elevation", m.elevationTiles},
                         {"imagery", m.imageryTiles},
                         {"per_zoom", perZoom},
                         {"on_disk", {{"elevation", onDisk.elevation}, {"imagery", onDisk.imagery}}}};
  // The NDVI layer (import --imagery-nir); null when the dataset has none.
  tiles["ndvi"] = m.ndvi ? nlohmann::json(m.ndviTiles) : nlohmann::json(nullptr);
  if (m.ndvi) tiles["on_disk"]["ndvi"] = onDisk.ndvi;
  // The landcover layer (import --landcover); null when the dataset has none.
  tiles["landcover"] = m.landcover ? nlohmann::json(m.landcoverTiles) : nlohmann::json(nullptr);
  if (m.landcover) tiles["on_disk"]["landcover"] = onDisk.landcover;
  // The canopy height layer (import --canopy-height); null when the dataset has none.
  tiles["canopy"] = m.canopyZoom ? nlohmann::json(m.canopyTiles) : nlohmann::json(nullptr);
  if (m.canopyZoom) tiles["on_disk"]["canopy"] = onDisk.canopy;
  return tiles;
}

// The TileJSON files beside the dataset (datasets/tilejson.h) that are there: datasets made
// before they existed have none.
nlohmann::json tileJsonJson(const datasets::DatasetMeta& m, const fs::path& dir) {
  nlohmann::json tileJson = nlohmann::json::object();
  for (const datasets::TileJsonFile& f : datasets::tileJsonFiles(m)) {
    std::error_code ec;
    if (fs::is_regular_file(dir / f.fileName, ec)) tileJson[f.layer] = f.fileName;
  }
  return tileJson;
}

}  // namespace

int runInfo(const InfoOptions& options, const Logger& log) {
  auto reader = datasets::DatasetReader::open(options.dataset);
  if (!reader) return reportError(log, reader.error());
  const datasets::DatasetMeta& m = reader->meta();

  nlohmann::json sources = nlohmann::json::array();
  std::set<std::string> crsNames;
  for (const auto& s : m.sources) {
    sources.push_back({{"role", s.role}, {"path", s.path}, {"crs", s.crs}, {"description", s.description}});
    crsNames.insert(s.crs);
  }
  ZoomCounts onDisk;
  const nlohmann::json perZoom = perZoomJson(countTiles(reader->dir()), m, onDisk);
  warnMismatches(options.dataset, m, onDisk, log);
  const nlohmann::json out = {
      {"name", m.name},
      {"path", fs::absolute(reader->dir()).lexically_normal().string()},
      {"format_version", m.formatVersion},
      {"crs",
       {{"sources", std::vector<std::string>(crsNames.begin(), crsNames.end())},
        {"tiles", geo::webMercatorCrs().name()}}},
      {"sources", sources},
      {"bounds",
       {{"west", m.bounds.westDeg},
        {"south", m.bounds.southDeg},
        {"east", m.bounds.eastDeg},
        {"north", m.bounds.northDeg}}},
      {"zoom", {{"min", m.minZoom}, {"max", m.maxZoom}}},
      {"height_m", {{"min", m.minHeightM}, {"max", m.maxHeightM}}},
      {"tile_size", m.tileSize},
      {"elevation_encoding", datasets::toString(m.elevationEncoding)},
      {"imagery_format", m.imagery ? nlohmann::json(datasets::toString(*m.imagery)) : nlohmann::json(nullptr)},
      {"landcover_scheme", m.landcover ? nlohmann::json(datasets::toString(*m.landcover)) : nlohmann::json(nullptr)},
      {"tiles", tilesJson(m, perZoom, onDisk)},
      {"bytes", m.bytes},
      {"bytes_on_disk", onDisk.bytes},
      {"attribution", m.attribution},
      {"tilejson", tileJsonJson(m, reader->dir())}};
  std::cout << out.dump(2) << "\n";
  return kExitOk;
}

}  // namespace vegstream::app
