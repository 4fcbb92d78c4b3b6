// MBTiles archives as a tile source (xyz_source.h). Spec: MBTiles 1.3,
// https://github.com/mapbox/mbtiles-spec/blob/master/1.3/spec.md — a SQLite database with a
// `metadata` table (name, value: bounds "W,S,E,N", minzoom, maxzoom, format) and a `tiles`
// table or view (zoom_level, tile_column, tile_row, tile_data) whose rows are TMS rows (row 0 =
// south). Opened read-only; one connection, its statements under a mutex (reads are short).

#include <cmath>
#include <mutex>
#include <sstream>

#include <sqlite3.h>

#include "datasets/message.h"
#include "datasets/tile_template.h"
#include "datasets/xyz_source.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

constexpr int kMaxTileBytes = 64 << 20;

class MbtilesSource final : public XyzSource {
 public:
  MbtilesSource(const fs::path& file, sqlite3* db) : XyzSource(file.string()), db_(db) {}
  ~MbtilesSource() override {
    sqlite3_finalize(readStmt_);
    sqlite3_close(db_);
  }
  const char* kind() const override { return "MBTiles"; }
  bool listsTiles() const override { return true; }
  XyzSourceExtent extent() const override { return extent_; }
  Result<std::vector<geo::TileId>> tilesAt(int z, const std::optional<geo::GeoBounds>& bounds, uint64_t) override;
  Result<std::optional<std::vector<uint8_t>>> read(const geo::TileId& id) override;
  std::string tileName(const geo::TileId& id) const override {
    return concat(name(), " tile ", geo::toString(id), " (TMS row ", flipTileRow(id.y, id.z), ")");
  }
  Status load();

 private:
  Error failure(const std::string& what) const {
    return makeError(ErrorKind::InvalidInput,
                     concat("'", name(), "' is not a valid MBTiles archive: ", what, ": ", sqlite3_errmsg(db_)));
  }
  Status readMetadata();

  sqlite3* db_ = nullptr;
  sqlite3_stmt* readStmt_ = nullptr;
  std::mutex mutex_;
  XyzSourceExtent extent_;
};

std::optional<geo::GeoBounds> parseBounds(const std::string& text) {
  std::stringstream ss(text);
  double v[4];
  char comma = 0;
  for (int i = 0; i < 4; ++i) {
    if (!(ss >> v[i])) return std::nullopt;
    if (i < 3 && (!(ss >> comma) || comma != ',')) return std::nullopt;
  }
  for (double d : v)
    if (!std::isfinite(d)) return std::nullopt;
  if (v[1] > v[3] || v[1] < -90 || v[3] > 90 || v[0] < -180 || v[2] > 180) return std::nullopt;
  return geo::GeoBounds{v[0], v[1], v[2], v[3]};
}

Status MbtilesSource::readMetadata() {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT name, value FROM metadata", -1, &s, nullptr) != SQLITE_OK)
    return failure("no metadata table");
  int rc;
  std::string format;
  while ((rc = sqlite3_step(s)) == SQLITE_ROW) {
    const auto* n = reinterpret_cast<const char*>(sqlite3_column_text(s, 0));
    const auto* v = reinterpret_cast<const char*>(sqlite3_column_text(s, 1));
    if (n == nullptr || v == nullptr) continue;
    const std::string key(n), value(v);
    char* end = nullptr;
    const long zoom = std::strtol(value.c_str(), &end, 10);
    const bool isZoom = !value.empty() && *end == '\0' && zoom >= 0 && zoom <= geo::kMaxTileZoom;
    if (key == "bounds") extent_.bounds = parseBounds(value);
    if (key == "minzoom" && isZoom) extent_.minZoom = static_cast<int>(zoom);
    if (key == "maxzoom" && isZoom) extent_.maxZoom = static_cast<int>(zoom);
    if (key == "format") format = value;
  }
  sqlite3_finalize(s);
  if (rc != SQLITE_DONE) return failure("reading metadata");
  if (format == "pbf" || format == "mvt")
    return makeError(ErrorKind::Unsupported,
                     concat("'", name(), "' holds vector tiles (format ", format, "); vegstream imports raster tiles"));
  if (!format.empty() && format != "png" && format != "jpg" && format != "jpeg" && format != "webp")
    return makeError(ErrorKind::Unsupported,
                     concat("'", name(), "' holds ", format, " tiles; vegstream reads png, jpg and webp"));
  return {};
}

Status MbtilesSource::load() {
  if (auto s = readMetadata(); !s) return s;
  const char* sql = "SELECT tile_data FROM tiles WHERE zoom_level = ?1 AND tile_column = ?2 AND tile_row = ?3";
  if (sqlite3_prepare_v2(db_, sql, -1, &readStmt_, nullptr) != SQLITE_OK) return failure("no usable tiles table");
  if (!extent_.maxZoom) {  // metadata without maxzoom: the tiles say
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_, "SELECT MIN(zoom_level), MAX(zoom_level) FROM tiles", -1, &s, nullptr) != SQLITE_OK)
      return failure("no usable tiles table");
    if (sqlite3_step(s) == SQLITE_ROW && sqlite3_column_type(s, 1) == SQLITE_INTEGER) {
      const int lo = sqlite3_column_int(s, 0), hi = sqlite3_column_int(s, 1);
      if (hi >= 0 && hi <= geo::kMaxTileZoom) extent_.minZoom = std::max(lo, 0), extent_.maxZoom = hi;
    }
    sqlite3_finalize(s);
  }
  return {};
}

Result<std::vector<geo::TileId>> MbtilesSource::tilesAt(int z, const std::optional<geo::GeoBounds>& bounds,
                                                        uint64_t maxTiles) {
  std::lock_guard lock(mutex_);
  sqlite3_stmt* s = nullptr;
  const char* sql = "SELECT tile_column, tile_row FROM tiles WHERE zoom_level = ?1 ORDER BY tile_column, tile_row";
  if (sqlite3_prepare_v2(db_, sql, -1, &s, nullptr) != SQLITE_OK) return failure("listing tiles");
  sqlite3_bind_int(s, 1, z);
  const auto ranges = bounds ? geo::tileRangesCovering(*bounds, z) : std::vector<geo::TileRange>{};
  std::vector<geo::TileId> ids;
  int rc;
  while ((rc = sqlite3_step(s)) == SQLITE_ROW) {
    const int64_t col = sqlite3_column_int64(s, 0), row = sqlite3_column_int64(s, 1), side = int64_t{1} << z;
    if (col < 0 || row < 0 || col >= side || row >= side) {
      sqlite3_finalize(s);
      return makeError(ErrorKind::InvalidInput, concat("'", name(), "' has a tile outside zoom ", z, "'s grid (column ",
                                                       col, ", row ", row, ")"));
    }
    const geo::TileId id{z, static_cast<int>(col), flipTileRow(static_cast<int>(row), z)};
    if (bounds && std::none_of(ranges.begin(), ranges.end(), [&](const auto& r) { return r.contains(id); })) continue;
    if (ids.size() >= maxTiles) {
      sqlite3_finalize(s);
      return makeError(ErrorKind::InvalidInput, concat("'", name(), "' has more than ", maxTiles, " tiles at zoom ", z,
                                                       " (a smaller --bounds or a lower --max-zoom)"));
    }
    ids.push_back(id);
  }
  sqlite3_finalize(s);
  if (rc != SQLITE_DONE) return failure("listing tiles");
  std::sort(ids.begin(), ids.end());
  return ids;
}

Result<std::optional<std::vector<uint8_t>>> MbtilesSource::read(const geo::TileId& id) {
  std::lock_guard lock(mutex_);
  sqlite3_reset(readStmt_);
  sqlite3_bind_int(readStmt_, 1, id.z);
  sqlite3_bind_int(readStmt_, 2, id.x);
  sqlite3_bind_int(readStmt_, 3, flipTileRow(id.y, id.z));
  const int rc = sqlite3_step(readStmt_);
  if (rc == SQLITE_DONE) return std::optional<std::vector<uint8_t>>();
  if (rc != SQLITE_ROW) return failure(concat("reading tile ", geo::toString(id)));
  const int n = sqlite3_column_bytes(readStmt_, 0);
  if (n > kMaxTileBytes)
    return makeError(ErrorKind::InvalidInput,
                     concat(tileName(id), " has ", n, " bytes; tiles stop at ", kMaxTileBytes));
  const auto* p = static_cast<const uint8_t*>(sqlite3_column_blob(readStmt_, 0));
  std::vector<uint8_t> bytes(p, p + (p ? n : 0));
  sqlite3_reset(readStmt_);
  return std::optional<std::vector<uint8_t>>(std::move(bytes));
}

}  // namespace

Result<std::unique_ptr<XyzSource>> openMbtilesSource(const fs::path& file) {
  if (Status s = checkArchiveFile(file, concat("MBTiles archive ", file)); !s) return s.error();
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY | SQLITE_OPEN_FULLMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    const std::string why = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    return makeError(ErrorKind::InvalidInput, concat("cannot open MBTiles archive ", file, ": ", why));
  }
  auto source = std::make_unique<MbtilesSource>(file, db);
  if (auto s = source->load(); !s) return s.error();
  return std::unique_ptr<XyzSource>(std::move(source));
}

}  // namespace vegstream::datasets
