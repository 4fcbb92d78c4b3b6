#pragma once
// Writes an MBTiles 1.3 archive for the tests (https://github.com/mapbox/mbtiles-spec/blob/master/1.3/spec.md)
// through SQLite: `metadata` (name, format, bounds, minzoom, maxzoom) and `tiles` with TMS rows
// (tile_row = 2^z − 1 − y), as gdal_translate and mb-util write them.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "geo/xyz_tiles.h"

namespace vegstream::testing {

// False (with `error` set) when SQLite refuses. `format`: "png", "jpg", "webp".
bool writeMbtiles(const std::filesystem::path& path, const std::map<geo::TileId, std::vector<uint8_t>>& tiles,
                  const std::string& format, std::string& error);

}  // namespace vegstream::testing
