#pragma once
// The dataset directory (DESIGN.md, "Dataset directory"): what every importer writes and the
// renderer and streamer read.
//
//   DIR/dataset.json                      DatasetMeta below, as JSON
//   DIR/elevation/{z}/{x}/{y}.png         RGBA PNG, height in RGB (terrarium or terrain-RGB),
//                                         alpha 0 = nodata (a mask, never a zero height)
//   DIR/imagery/{z}/{x}/{y}.jpg|png       RGB JPEG or RGBA PNG (alpha 0 = no data)
//   DIR/ndvi/{z}/{x}/{y}.png              optional: 8-bit grey PNG, NDVI from the near-infrared
//                                         and red bands (tile_codec.h ndviToByte; 0 = no data)
//   DIR/landcover/{z}/{x}/{y}.png         optional: 8-bit grey PNG, the class code as the source
//                                         stores it (landcover.h; 0 = no data)
//   DIR/canopy/{z}/{x}/{y}.png            optional: 16-bit grey PNG, canopy height in decimetres
//                                         at canopy.zoom, its max pyramid below (canopy.h;
//                                         65535 = no data)
//
// XYZ Web Mercator scheme, rows counted from the north, 256-pixel tiles, pixel (i, j) of a tile
// sampled at its centre, so any static server can serve a dataset and QGIS/MapLibre read it.
// Tiles are written only where the source has data; a missing tile is "no data there".

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "datasets/colour_calibration.h"
#include "datasets/landcover_classes.h"
#include "geo/bounds.h"
#include "geo/xyz_tiles.h"

namespace vegstream::datasets {

constexpr int kDatasetFormatVersion = 1;
constexpr int kTileSize = 256;

enum class ElevationEncoding { Terrarium, TerrainRgb };
enum class ImageryFormat { Jpeg, Png };

const char* toString(ElevationEncoding e);                                  // "terrarium", "terrain-rgb"
const char* toString(ImageryFormat f);                                      // "jpeg", "png"
Result<ElevationEncoding> parseElevationEncoding(const std::string& text);  // error names the text

struct SourceInfo {
  std::string role;         // "elevation", "imagery"
  std::string path;         // as given by the user, or the tile template
  std::string crs;          // Crs::name(), e.g. "WGS 84 (EPSG:4326)"
  std::string description;  // size, pixel size, …
  // Provenance (optional; absent in datasets written before GDAL import): the CRS as an EPSG
  // code ("EPSG:27700"), or as PROJJSON text when it has none; the ground pixel size at the
  // source's centre; GDAL's driver ("GTiff", "VRT", …).
  std::string crsCode;
  std::string crsProjjson;
  double resolutionM = 0.0;
  std::string driver;
};

// How the imagery's acquisition shading was taken out (deshading.h): the sun it was taken under
// and where that came from. dataset.json's "imagery.radiometry.deshading".
struct DeshadingRecord {
  std::string source = "none";  // "imagery datetime", "given" (--imagery-sun), "estimated" or "none"
  double sunAzimuthDeg = 0.0;   // clockwise from north; unless source is "none"
  double sunElevationDeg = 0.0;
  double directFraction = 0.0;  // k of deshading.h
  std::string note;             // why none, or how well the estimate fits; may be empty
};

// What the imagery's bytes mean (radiometry.h), dataset.json's "imagery.radiometry". Absent in
// datasets imported before it existed (their bytes are display-stretched or as stored).
struct RadiometryRecord {
  std::string method;                               // "reflectance", "srgb" or "stretch"
  std::optional<double> scale, offset;              // reflectance: ρ = DN · scale + offset
  std::optional<std::array<double, 3>> darkObject;  // reflectance: each band's (R, G, B) dark object
  std::optional<double> darkObjectPercentile;       // the percentile taken as the dark object
  std::optional<double> darkObjectReflectance;      // the reflectance assumed for it
  std::optional<DeshadingRecord> deshading;
};

struct DatasetMeta {
  int formatVersion = kDatasetFormatVersion;
  std::string name;
  geo::GeoBounds bounds;  // extent of the data, degrees
  int minZoom = 0;
  int maxZoom = 0;
  double minHeightM = 0.0;  // over all valid heights at maxZoom
  double maxHeightM = 0.0;
  ElevationEncoding elevationEncoding = ElevationEncoding::Terrarium;
  std::optional<ImageryFormat> imagery;  // nullopt: no imagery tiles
  // When the imagery was taken, ISO 8601 with a zone (`import --imagery-datetime`, checked by
  // geo/datetime.h where it is used); empty: unknown. dataset.json's "imagery.datetime".
  std::string imageryDatetime;
  std::optional<RadiometryRecord> radiometry;  // dataset.json's "imagery.radiometry" (optional)
  // The colour calibration the species choice sees (colour_calibration.h); nullopt: identity.
  std::optional<ColourCalibrationRecord> colourCalibration;  // "imagery.colour_calibration"
  int tileSize = kTileSize;
  std::string attribution;
  std::vector<SourceInfo> sources;
  uint64_t elevationTiles = 0;
  uint64_t imageryTiles = 0;
  bool ndvi = false;  // an NDVI layer (import --imagery-nir); false: datasets as before
  uint64_t ndviTiles = 0;
  // A landcover layer (import --landcover) and the scheme of its codes; nullopt: none (and in
  // datasets written before the layer existed).
  std::optional<LandcoverScheme> landcover;
  uint64_t landcoverTiles = 0;
  // A canopy height layer (import --canopy-height, canopy.h): the zoom its heights were sampled
  // at (lower zooms hold its pyramid); nullopt: none.
  std::optional<int> canopyZoom;
  uint64_t canopyTiles = 0;
  uint64_t bytes = 0;  // all tile files together
};

// dataset.json ↔ DatasetMeta. Reading checks every field and names the file and the field.
Result<DatasetMeta> readDatasetMeta(const std::filesystem::path& datasetDir);
// The same check of dataset.json's text from anywhere (an HTTP source): errors name
// `sourceName` (a path or URL) and the field.
Result<DatasetMeta> parseDatasetMeta(const std::string& jsonText, const std::string& sourceName);
Status writeDatasetMeta(const std::filesystem::path& datasetDir, const DatasetMeta& meta);

std::filesystem::path elevationTilePath(const std::filesystem::path& datasetDir, const geo::TileId& id);
std::filesystem::path imageryTilePath(const std::filesystem::path& datasetDir, const geo::TileId& id, ImageryFormat f);
std::filesystem::path ndviTilePath(const std::filesystem::path& datasetDir, const geo::TileId& id);
std::filesystem::path landcoverTilePath(const std::filesystem::path& datasetDir, const geo::TileId& id);

}  // namespace vegstream::datasets
