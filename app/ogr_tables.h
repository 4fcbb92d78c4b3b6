#pragma once
// Tables of points written through GDAL/OGR, in the formats GIS tools read: GeoPackage, GeoJSON
// (RFC 7946) and CSV. Used by `vegstream plants` (app/plants_export.h); knows nothing of plants.
//
//   GeoPackage  every table a layer of one file (layer name = table name), 2D point geometry
//               "geom" in EPSG:4326 (lon, lat), one attribute field per column, written in one
//               transaction per layer, with the GeoPackage's R-tree spatial index.
//   GeoJSON     one table per file: a FeatureCollection (RFC7946=YES: lon/lat WGS 84, no "crs"
//               member), 2D points with 10 decimals (about 10 µm), the columns as properties.
//   CSV         one table per file: no geometry column but "lon" and "lat" (WGS 84 degrees)
//               first, then the columns; a header line, "\n" line ends, strings quoted only
//               where needed (OGR's CSV driver with STRING_QUOTING=IF_NEEDED). pandas, QGIS
//               ("Delimited text", lon/lat found by name) and GDAL (-oo X_POSSIBLE_NAMES=lon
//               -oo Y_POSSIBLE_NAMES=lat) read it.
//
// Real values are written as given; a caller that wants fixed digits rounds them first (OGR
// prints the shortest text that reads back to the same double).
//
// Every file appears whole or not at all (DESIGN.md): each target is written by GDAL to a
// temporary name beside it that keeps the format's extension (the CSV driver writes a
// directory for any other name), fsync'ed, and only when every file of the call is complete
// are they renamed into place; a failure removes every temporary (and SQLite's journal beside
// a GeoPackage) and every file of the call already renamed. GDAL's own messages never reach
// stderr: they are collected, and the first failure is the error's message.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/result.h"

namespace vegstream::app {

enum class TableFormat { GeoPackage, GeoJson, Csv };

struct TableColumn {
  enum class Type { Real, Text };
  std::string name;
  Type type = Type::Real;
};

// A value of one column: a double for Real, text for Text (the view need only live until the
// row callback is called again).
using TableValue = std::variant<double, std::string_view>;

struct PointTable {
  std::string name;  // the layer name (GeoPackage), the FeatureCollection's "name" (GeoJSON)
  std::string description;  // GeoPackage: gpkg_contents.description; elsewhere unused
  std::vector<TableColumn> columns;
  size_t rowCount = 0;
  // Fills row i (0 … rowCount − 1): its point (WGS 84 degrees) and one value per column, in
  // column order (values.size() == columns.size()).
  std::function<void(size_t i, double& lonDeg, double& latDeg, std::span<TableValue> values)> row;
};

// One file to write: the tables it holds (GeoPackage: any number ≥ 1; GeoJSON and CSV: one).
struct TableFile {
  std::filesystem::path path;  // "/vsistdout/": standard output (GeoJSON and CSV only; not staged)
  std::vector<const PointTable*> tables;
};

// Writes every file, all or none (above). Errors: Io with GDAL's message and the file's path
// (as the caller named it); InvalidInput for a GeoPackage to stdout or a GeoJSON / CSV file of
// more than one table.
Status writeTableFiles(TableFormat format, std::span<const TableFile> files);

}  // namespace vegstream::app
