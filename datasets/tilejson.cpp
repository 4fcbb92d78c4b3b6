// TileJSON 3.0.0 files beside a dataset (tilejson.h): built from DatasetMeta, the same numbers
// dataset.json holds (nlohmann prints both with the same shortest round-trip digits).

#include "datasets/tilejson.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "datasets/message.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// MapLibre's raster-dem "encoding" of an elevation encoding.
const char* mapLibreEncoding(ElevationEncoding e) { return e == ElevationEncoding::Terrarium ? "terrarium" : "mapbox"; }

json document(const DatasetMeta& m, const std::string& layer, const std::string& tiles, const std::string& what) {
  const geo::GeoBounds& b = m.bounds;
  return {{"tilejson", "3.0.0"},
          {"name", concat(m.name, " ", layer)},
          {"description", concat(what, " of the vegstream dataset '", m.name, "' (XYZ Web Mercator, ", m.tileSize,
                                 "-pixel tiles; the template is relative to the dataset root)")},
          {"attribution", m.attribution},
          {"scheme", "xyz"},
          {"tiles", json::array({tiles})},
          {"minzoom", m.minZoom},
          {"maxzoom", m.maxZoom},
          {"bounds", json::array({b.westDeg, b.southDeg, b.eastDeg, b.northDeg})},
          {"center", json::array({0.5 * (b.westDeg + b.eastDeg), 0.5 * (b.southDeg + b.northDeg), m.minZoom})},
          {"tileSize", m.tileSize}};
}

}  // namespace

std::string tileJsonFileName(const std::string& layer) { return layer + ".tilejson.json"; }

std::vector<TileJsonFile> tileJsonFiles(const DatasetMeta& m) {
  std::vector<std::pair<std::string, json>> docs;
  json elevation = document(m, "elevation", "elevation/{z}/{x}/{y}.png",
                            concat("Elevation, ", toString(m.elevationEncoding), "-encoded RGB PNG (alpha 0: no data),"));
  elevation["encoding"] = mapLibreEncoding(m.elevationEncoding);
  docs.emplace_back("elevation", std::move(elevation));
  if (m.imagery) {
    const char* ext = *m.imagery == ImageryFormat::Jpeg ? "jpg" : "png";
    docs.emplace_back("imagery", document(m, "imagery", concat("imagery/{z}/{x}/{y}.", ext),
                                          concat("Imagery (albedo, sRGB ", ext, "),")));
  }
  if (m.ndvi)
    docs.emplace_back("ndvi", document(m, "ndvi", "ndvi/{z}/{x}/{y}.png",
                                       "NDVI, 8-bit grey PNG (0: no data, 1 … 255: NDVI −1 … 1),"));
  std::vector<TileJsonFile> files;
  for (auto& [layer, doc] : docs) files.push_back({layer, tileJsonFileName(layer), doc.dump(2) + "\n"});
  return files;
}

Status writeTileJsons(const fs::path& datasetDir, const DatasetMeta& meta) {
  for (const TileJsonFile& f : tileJsonFiles(meta)) {
    const fs::path file = datasetDir / f.fileName;
    const Status s = writeTextAtomically(file, f.text);
    if (!s) return s;
  }
  return {};
}

}  // namespace vegstream::datasets
