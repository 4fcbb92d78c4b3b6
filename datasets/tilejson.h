#pragma once
// TileJSON 3.0.0 (https://github.com/mapbox/tilejson-spec/tree/master/3.0.0) beside every
// dataset, so MapLibre, QGIS and other tile clients can show a dataset's layers as they are:
//
//   DIR/elevation.tilejson.json   the elevation (raster-dem: "encoding" terrarium | mapbox)
//   DIR/imagery.tilejson.json     the imagery, when the dataset has imagery
//   DIR/ndvi.tilejson.json        the NDVI layer, when the dataset has one
//
// Each holds "tilejson": "3.0.0", "name" ("<dataset> elevation", …), "description",
// "attribution" (dataset.json's), "scheme": "xyz", "tiles": one template *relative to the
// dataset root* ("imagery/{z}/{x}/{y}.jpg"), "minzoom"/"maxzoom" (dataset.json's zoom range),
// "bounds" [west, south, east, north] (dataset.json's bounds, degrees), "center" [lon, lat,
// minzoom] (the middle of the bounds), "tileSize": 256 (not in the spec; MapLibre reads it from
// a TileJSON and assumes 512 without it) and, for elevation, "encoding": "terrarium" for
// terrarium tiles and "mapbox" for terrain-RGB (MapLibre's raster-dem key).
//
// The files lie at the dataset root, so a client that resolves the template against the
// TileJSON's own URL (RFC 3986) finds the tiles; one that does not (MapLibre GL JS uses tile
// URLs as given) needs them made absolute by whoever serves the dataset. dataset.json is not
// changed by any of this: the TileJSON files are derived from it.

#include <filesystem>
#include <string>
#include <vector>

#include "core/result.h"
#include "datasets/dataset_format.h"

namespace vegstream::datasets {

// One TileJSON file of a dataset: its layer ("elevation", "imagery", "ndvi"), its file name at
// the dataset root and its text.
struct TileJsonFile {
  std::string layer;
  std::string fileName;  // e.g. "imagery.tilejson.json"
  std::string text;      // the JSON document, 2-space indented, ending in a newline
};

// The TileJSON documents of a dataset described by meta (elevation always; imagery and NDVI
// when meta has them).
std::vector<TileJsonFile> tileJsonFiles(const DatasetMeta& meta);

// The file name of a layer's TileJSON ("<layer>.tilejson.json").
std::string tileJsonFileName(const std::string& layer);

// Writes every tileJsonFiles(meta) document into datasetDir, each atomically
// (core/atomic_file.h). Errors: Io naming the file.
Status writeTileJsons(const std::filesystem::path& datasetDir, const DatasetMeta& meta);

}  // namespace vegstream::datasets
