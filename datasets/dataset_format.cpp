// dataset.json ↔ DatasetMeta, and the tile paths of a dataset directory (dataset_format.h).
// The JSON is what other tools and people read, so field names are plain snake_case and every
// field is checked on the way in: a bad one is named in the error together with the file.
//
//   { "format_version": 1, "name": "zion",
//     "bounds": { "west": …, "south": …, "east": …, "north": … },      degrees
//     "min_zoom": 9, "max_zoom": 12, "tile_size": 256,
//     "min_height_m": 1024.0, "max_height_m": 2892.0,
//     "elevation": { "encoding": "terrarium", "tiles": "elevation/{z}/{x}/{y}.png", "tile_count": N },
//     "imagery":   { "format": "jpeg", "tiles": "imagery/{z}/{x}/{y}.jpg", "tile_count": N,
//                    "datetime": "2015-08-18T17:58:00Z" (optional: when it was taken),
//                    "radiometry": { "method": "reflectance", "scale": 2e-5, "offset": -0.1,
//                                    "dark_object": [r, g, b], "dark_object_percentile": 0.01,
//                                    "dark_object_reflectance": 0.01,
//                                    "deshading": { "source": "imagery datetime", "sun_azimuth_deg": …,
//                                                   "sun_elevation_deg": …, "direct_fraction": 0.8,
//                                                   "note": "…" } } (optional),
//                    "colour_calibration": { … } (optional: colour_calibration_json.h) }  (or null)
//     "ndvi":      { "encoding": "ndvi8", "tiles": "ndvi/{z}/{x}/{y}.png", "tile_count": N }  (or null)
//     "landcover": { "encoding": "class8", "scheme": "worldcover", "tiles": "landcover/{z}/{x}/{y}.png",
//                    "tile_count": N }  (or null)
//     "canopy":    { "encoding": "decimetre16", "zoom": Z, "tiles": "canopy/{z}/{x}/{y}.png",
//                    "tile_count": N }  (or null; import --canopy-height, canopy.h)
//     "attribution": "…", "sources": [ { "role", "path", "crs", "description" } ], "bytes": N }
//
// "ndvi" (import --imagery-nir) came after format version 1 was fixed: a dataset.json without
// the key reads as one without an NDVI layer, so datasets written before it keep working; a key
// that is there is checked like every other field. The same holds for "imagery.datetime" and
// "imagery.radiometry" (and each of radiometry's own keys but "method"). "ndvi8" is tile_codec.h's ndviToByte.
// "landcover" (import --landcover, issue 40) likewise: absent or null is no layer; "class8" is
// landcover.h's class code per byte, "scheme" one of landcover_classes.h's schemes.

#include "datasets/dataset_format.h"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/json_text.h"
#include "core/printable.h"
#include "core/regular_file.h"
#include "datasets/dataset_field_reader.h"
#include "datasets/dataset_layers_json.h"
#include "datasets/message.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace dataset_json;

constexpr const char* kMetaFile = "dataset.json";
constexpr int kMaxProjjsonDepth = 64;  // real PROJJSON nests about 6 deep

// format_version, name, bounds, the zooms, tile_size and the height range.
Status parseHeader(const json& j, const FieldReader& f, DatasetMeta& m) {
  int64_t version = 0;
  VEG_TRY_ASSIGN(version, f.integer(j, "format_version", "format_version", 1, 1'000'000));
  if (version != kDatasetFormatVersion)
    return makeError(
        ErrorKind::Unsupported,
        f.bad("format_version", concat("is ", version, "; this vegstream reads version ", kDatasetFormatVersion))
            .message);
  m.formatVersion = static_cast<int>(version);
  VEG_TRY_ASSIGN(m.name, f.text(j, "name", "name"));

  const json* b = nullptr;
  VEG_TRY_ASSIGN(b, f.get(j, "bounds", "bounds"));
  if (!b->is_object()) return f.bad("bounds", "must be an object with west, south, east, north");
  VEG_TRY_ASSIGN(m.bounds.westDeg, f.number(*b, "west", "bounds.west", -180.0, 180.0));
  VEG_TRY_ASSIGN(m.bounds.southDeg, f.number(*b, "south", "bounds.south", -90.0, 90.0));
  VEG_TRY_ASSIGN(m.bounds.eastDeg, f.number(*b, "east", "bounds.east", -180.0, 180.0));
  VEG_TRY_ASSIGN(m.bounds.northDeg, f.number(*b, "north", "bounds.north", -90.0, 90.0));
  if (m.bounds.southDeg > m.bounds.northDeg) return f.bad("bounds", "has south greater than north");

  int64_t z = 0;
  VEG_TRY_ASSIGN(z, f.integer(j, "min_zoom", "min_zoom", 0, geo::kMaxTileZoom));
  m.minZoom = static_cast<int>(z);
  VEG_TRY_ASSIGN(z, f.integer(j, "max_zoom", "max_zoom", 0, geo::kMaxTileZoom));
  m.maxZoom = static_cast<int>(z);
  if (m.minZoom > m.maxZoom) return f.bad("min_zoom", "is greater than max_zoom");
  VEG_TRY_ASSIGN(z, f.integer(j, "tile_size", "tile_size", 1, 4096));
  m.tileSize = static_cast<int>(z);
  VEG_TRY_ASSIGN(m.minHeightM, f.number(j, "min_height_m", "min_height_m", -11000.0, 9000.0));
  VEG_TRY_ASSIGN(m.maxHeightM, f.number(j, "max_height_m", "max_height_m", -11000.0, 9000.0));
  if (m.minHeightM > m.maxHeightM) return f.bad("min_height_m", "is greater than max_height_m");
  return {};
}

// "elevation": its encoding and tile count.
Status parseElevation(const json& j, const FieldReader& f, DatasetMeta& m) {
  const json* e = nullptr;
  VEG_TRY_ASSIGN(e, f.get(j, "elevation", "elevation"));
  if (!e->is_object()) return f.bad("elevation", "must be an object");
  std::string enc;
  VEG_TRY_ASSIGN(enc, f.text(*e, "encoding", "elevation.encoding"));
  auto parsed = parseElevationEncoding(enc);
  if (!parsed)
    return f.bad("elevation.encoding", concat("is '", printable(enc), "'; expected terrarium or terrain-rgb"));
  m.elevationEncoding = *parsed;
  int64_t count = 0;
  VEG_TRY_ASSIGN(count, f.integer(*e, "tile_count", "elevation.tile_count", 0, INT64_MAX));
  m.elevationTiles = static_cast<uint64_t>(count);
  return {};
}

// One entry of "sources" (at "sources[i]"); the optional keys are taken when of the right type.
Result<SourceInfo> parseSource(const json& s, const std::string& at, const FieldReader& f) {
  if (!s.is_object()) return f.bad(at, "must be an object");
  SourceInfo info;
  VEG_TRY_ASSIGN(info.role, f.text(s, "role", at + ".role"));
  VEG_TRY_ASSIGN(info.path, f.text(s, "path", at + ".path"));
  VEG_TRY_ASSIGN(info.crs, f.text(s, "crs", at + ".crs"));
  VEG_TRY_ASSIGN(info.description, f.text(s, "description", at + ".description"));
  if (s.contains("crs_epsg") && s["crs_epsg"].is_string()) info.crsCode = s["crs_epsg"].get<std::string>();
  if (s.contains("crs_projjson") && s["crs_projjson"].is_object()) {
    // dump() recurses once per level: a PROJJSON nested deeper than any real one is refused.
    if (!jsonDepthAtMost(s["crs_projjson"], kMaxProjjsonDepth))
      return f.bad(at + ".crs_projjson", concat("is nested more than ", kMaxProjjsonDepth, " levels deep"));
    info.crsProjjson = s["crs_projjson"].dump();
  }
  if (s.contains("resolution_m") && s["resolution_m"].is_number()) info.resolutionM = s["resolution_m"].get<double>();
  if (s.contains("driver") && s["driver"].is_string()) info.driver = s["driver"].get<std::string>();
  return info;
}

Result<DatasetMeta> parseMeta(const json& j, const FieldReader& f) {
  if (!j.is_object()) return f.bad("(top level)", "must be a JSON object");
  DatasetMeta m;
  if (Status st = parseHeader(j, f, m); !st) return st.error();
  if (Status st = parseElevation(j, f, m); !st) return st.error();

  const json* im = nullptr;
  VEG_TRY_ASSIGN(im, f.get(j, "imagery", "imagery"));
  if (!im->is_null())
    if (Status st = parseImagery(*im, f, m); !st) return st.error();

  if (auto nd = j.find("ndvi"); nd != j.end() && !nd->is_null())
    if (Status st = parseNdvi(*nd, f, m); !st) return st.error();

  if (auto lc = j.find("landcover"); lc != j.end() && !lc->is_null())
    if (Status s = parseLandcover(*lc, f, m); !s) return s.error();
  if (auto c = j.find("canopy"); c != j.end() && !c->is_null())
    if (Status s = parseCanopy(*c, f, m); !s) return s.error();

  VEG_TRY_ASSIGN(m.attribution, f.text(j, "attribution", "attribution"));
  const json* src = nullptr;
  VEG_TRY_ASSIGN(src, f.get(j, "sources", "sources"));
  if (!src->is_array()) return f.bad("sources", "must be an array");
  for (size_t i = 0; i < src->size(); ++i) {
    SourceInfo info;
    VEG_TRY_ASSIGN(info, parseSource((*src)[i], concat("sources[", i, "]"), f));
    m.sources.push_back(std::move(info));
  }
  int64_t count = 0;
  VEG_TRY_ASSIGN(count, f.integer(j, "bytes", "bytes", 0, INT64_MAX));
  m.bytes = static_cast<uint64_t>(count);
  return m;
}

#undef VEG_TRY_ASSIGN

json toJson(const DatasetMeta& m) {
  json sources = json::array();
  for (const auto& s : m.sources)
  {
    json one = {{"role", s.role}, {"path", s.path}, {"crs", s.crs}, {"description", s.description}};
    if (!s.crsCode.empty()) one["crs_epsg"] = s.crsCode;
    if (s.crsCode.empty() && !s.crsProjjson.empty()) one["crs_projjson"] = json::parse(s.crsProjjson, nullptr, false);
    if (s.resolutionM > 0.0) one["resolution_m"] = s.resolutionM;
    if (!s.driver.empty()) one["driver"] = s.driver;
    sources.push_back(std::move(one));
  }
  return json{{"format_version", m.formatVersion},
              {"name", m.name},
              {"bounds",
               {{"west", m.bounds.westDeg},
                {"south", m.bounds.southDeg},
                {"east", m.bounds.eastDeg},
                {"north", m.bounds.northDeg}}},
              {"min_zoom", m.minZoom},
              {"max_zoom", m.maxZoom},
              {"tile_size", m.tileSize},
              {"min_height_m", m.minHeightM},
              {"max_height_m", m.maxHeightM},
              {"elevation",
               {{"encoding", toString(m.elevationEncoding)},
                {"tiles", "elevation/{z}/{x}/{y}.png"},
                {"tile_count", m.elevationTiles}}},
              {"imagery", imageryJson(m)},
              {"ndvi", ndviJson(m)},
              {"landcover", landcoverJson(m)},
              {"canopy", canopyJson(m)},
              {"attribution", m.attribution},
              {"sources", sources},
              {"bytes", m.bytes}};
}

}  // namespace

const char* toString(ElevationEncoding e) { return e == ElevationEncoding::Terrarium ? "terrarium" : "terrain-rgb"; }
const char* toString(ImageryFormat f) { return f == ImageryFormat::Jpeg ? "jpeg" : "png"; }

Result<ElevationEncoding> parseElevationEncoding(const std::string& text) {
  if (text == "terrarium") return ElevationEncoding::Terrarium;
  if (text == "terrain-rgb" || text == "terrainrgb" || text == "mapbox") return ElevationEncoding::TerrainRgb;
  return makeError(ErrorKind::InvalidInput,
                   concat("elevation encoding '", text, "' is not known; expected terrarium or terrain-rgb"));
}

Result<DatasetMeta> readDatasetMeta(const fs::path& datasetDir) {
  const fs::path file = datasetDir / kMetaFile;
  std::error_code ec;
  if (!fs::exists(datasetDir, ec)) return makeError(ErrorKind::NotFound, concat(datasetDir, " does not exist"));
  // Only a regular file of at most the ceiling is read (a FIFO, a directory or a 200 MB file is
  // refused at once, core/regular_file.h).
  auto text = readRegularFile(file, kDatasetJsonCeiling);
  if (!text && text.error().kind == ErrorKind::NotFound)
    return makeError(ErrorKind::NotFound, concat(datasetDir, " is not a vegstream dataset: it has no dataset.json"));
  if (!text) return text.error();
  return parseDatasetMeta(*text, file.string());
}

Result<DatasetMeta> parseDatasetMeta(const std::string& jsonText, const std::string& sourceName) {
  // A broken text (a number no double holds, "1e9999", included) is a parse error naming the line
  // and column; the walk checks every type before reading, and the catch keeps a missed case an
  // error value.
  json j;
  try {
    j = json::parse(jsonText);
  } catch (const json::parse_error& e) {
    return makeError(ErrorKind::InvalidInput, concat("'", printablePath(sourceName), "' is not valid JSON: ",
                                                     jsonParseErrorText(jsonText, e.byte, e.what())));
  } catch (const json::exception& e) {  // a number no double holds ("1e9999"): no position
    return makeError(ErrorKind::InvalidInput,
                     concat("'", printablePath(sourceName), "' is not valid JSON: ", jsonExceptionText(e.what())));
  }
  try {
    return parseMeta(j, FieldReader(sourceName));
  } catch (const json::exception& e) {
    return makeError(ErrorKind::InvalidInput,
                     concat("'", printablePath(sourceName), "': ", jsonExceptionText(e.what())));
  }
}

Status writeDatasetMeta(const fs::path& datasetDir, const DatasetMeta& meta) {
  const fs::path file = datasetDir / kMetaFile;
  const std::string text = toJson(meta).dump(2) + "\n";
  return writeTextAtomically(file, text);
}

fs::path elevationTilePath(const fs::path& datasetDir, const geo::TileId& id) {
  return datasetDir / "elevation" / std::to_string(id.z) / std::to_string(id.x) / concat(id.y, ".png");
}

fs::path imageryTilePath(const fs::path& datasetDir, const geo::TileId& id, ImageryFormat f) {
  return datasetDir / "imagery" / std::to_string(id.z) / std::to_string(id.x) / concat(id.y, ".", imageryExtension(f));
}

fs::path ndviTilePath(const fs::path& datasetDir, const geo::TileId& id) {
  return datasetDir / "ndvi" / std::to_string(id.z) / std::to_string(id.x) / concat(id.y, ".png");
}

fs::path landcoverTilePath(const fs::path& datasetDir, const geo::TileId& id) {
  return datasetDir / "landcover" / std::to_string(id.z) / std::to_string(id.x) / concat(id.y, ".png");
}

}  // namespace vegstream::datasets
