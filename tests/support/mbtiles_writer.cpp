// The tests' MBTiles writer (mbtiles_writer.h).

#include "tests/support/mbtiles_writer.h"

#include <algorithm>
#include <cstdio>

#include <sqlite3.h>

namespace vegstream::testing {

bool writeMbtiles(const std::filesystem::path& path, const std::map<geo::TileId, std::vector<uint8_t>>& tiles,
                  const std::string& format, std::string& error) {
  std::filesystem::remove(path);
  sqlite3* db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) {
    error = sqlite3_errmsg(db);
    sqlite3_close(db);
    return false;
  }
  int minZ = 99, maxZ = 0;
  double w = 180, s = 90, e = -180, n = -90;
  for (const auto& [id, bytes] : tiles) {
    minZ = std::min(minZ, id.z), maxZ = std::max(maxZ, id.z);
    const auto b = geo::tileBoundsLonLat(id);
    w = std::min(w, b.westDeg), s = std::min(s, b.southDeg), e = std::max(e, b.eastDeg), n = std::max(n, b.northDeg);
  }
  char bounds[160];
  std::snprintf(bounds, sizeof bounds, "%.9f,%.9f,%.9f,%.9f", w, s, e, n);
  std::string sql =
      "CREATE TABLE metadata (name text, value text);"
      "CREATE TABLE tiles (zoom_level integer, tile_column integer, tile_row integer, tile_data blob);"
      "CREATE UNIQUE INDEX tile_index on tiles (zoom_level, tile_column, tile_row);"
      "INSERT INTO metadata VALUES ('name', 'test'), ('type', 'baselayer'), ('version', '1'),"
      "('format', '" + format + "'), ('bounds', '" + bounds + "'), ('minzoom', '" + std::to_string(minZ) +
      "'), ('maxzoom', '" + std::to_string(maxZ) + "');";
  char* message = nullptr;
  bool ok = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) == SQLITE_OK;
  sqlite3_stmt* insert = nullptr;
  ok = ok && sqlite3_prepare_v2(db, "INSERT INTO tiles VALUES (?1, ?2, ?3, ?4)", -1, &insert, nullptr) == SQLITE_OK;
  for (auto it = tiles.begin(); ok && it != tiles.end(); ++it) {
    const geo::TileId& id = it->first;
    sqlite3_bind_int(insert, 1, id.z);
    sqlite3_bind_int(insert, 2, id.x);
    sqlite3_bind_int(insert, 3, (1 << id.z) - 1 - id.y);  // TMS row
    sqlite3_bind_blob(insert, 4, it->second.data(), static_cast<int>(it->second.size()), SQLITE_TRANSIENT);
    ok = sqlite3_step(insert) == SQLITE_DONE;
    sqlite3_reset(insert);
  }
  if (!ok) error = message ? message : sqlite3_errmsg(db);
  sqlite3_free(message);
  sqlite3_finalize(insert);
  sqlite3_close(db);
  return ok;
}

}  // namespace vegstream::testing
