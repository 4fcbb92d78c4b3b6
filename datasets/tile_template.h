#pragma once
// Tile address templates of the XYZ / TMS conventions, as Leaflet, OpenLayers, QGIS and GDAL
// write them: "DIR/{z}/{x}/{y}.png" or "https://host/tiles/{z}/{x}/{-y}.png".
//
//   {z}   the zoom
//   {x}   the column, from 180°W eastwards
//   {y}   the row counted from the NORTH edge (XYZ, "slippy map", geo/xyz_tiles.h)
//   {-y}  the row counted from the SOUTH edge (TMS, OSGeo Tile Map Service Specification):
//         tmsRow = 2^z − 1 − y
//
// Each of {z} and {x} must appear exactly once, and exactly one of {y} / {-y} once; any other
// "{…}" (e.g. Leaflet's {s} subdomains or {r} retina suffix) is refused rather than sent to a
// server or looked for on disk as it is. A template is a URL when it starts with http:// or
// https:// (case-insensitive), else a local path.

#include <string>

#include "core/result.h"
#include "geo/xyz_tiles.h"

namespace vegstream::datasets {

struct TileTemplate {
  std::string text;      // as the user gave it
  bool isUrl = false;    // http:// or https://
  bool tmsRows = false;  // {-y}
};

// Errors: InvalidInput naming the template and what is wrong with it.
Result<TileTemplate> parseTileTemplate(const std::string& text);

// The template with the placeholders replaced by the tile's numbers ({-y} by the TMS row).
std::string expandTileTemplate(const TileTemplate& tmpl, const geo::TileId& id);

// The XYZ row of a TMS row at zoom z, and back (the same formula both ways).
int flipTileRow(int row, int z);

// True when the text starts with http:// or https:// (case-insensitive).
bool looksLikeHttpUrl(const std::string& text);

}  // namespace vegstream::datasets
