#pragma once
// Where `vegstream import --xyz-elevation / --xyz-imagery` read existing tiles from
// (DESIGN.md "import": XYZ / MBTiles / PMTiles by path or URL). One interface, four kinds:
//
//   a path template   "DIR/{z}/{x}/{y}.png" (or {-y}): the files found below DIR
//   a URL template    "https://host/{z}/{x}/{-y}.png": nothing to list, tiles asked for one by
//                     one (404 = no tile there); bounds and zoom come from the options
//   MBTiles           "FILE.mbtiles" (local path): SQLite, `tiles` table or view with TMS rows,
//                     `metadata` (bounds, minzoom, maxzoom, format) — MBTiles 1.3,
//                     https://github.com/mapbox/mbtiles-spec/blob/master/1.3/spec.md
//   PMTiles v3        "FILE.pmtiles" or "https://host/FILE.pmtiles" (HTTP Range requests),
//                     pmtiles_format.h
//
// Which kind: a text with "{z}" is a template (a URL when it starts with http:// or https://);
// else the name's extension (.mbtiles, .pmtiles), else a local file's first bytes (SQLite's or
// PMTiles' magic). The tiles' bytes are handed out encoded (PNG, JPEG, WebP) for the tile codec.
// read() is thread-safe: the importer's workers call it at once.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "datasets/http_fetch.h"
#include "geo/bounds.h"
#include "geo/xyz_tiles.h"

namespace vegstream::datasets {

// What a source says about itself; nullopt where it says nothing.
struct XyzSourceExtent {
  std::optional<geo::GeoBounds> bounds;  // archives' metadata / header
  std::optional<int> minZoom, maxZoom;   // archives' metadata / header; a directory: its files
};

class XyzSource {
 public:
  virtual ~XyzSource() = default;

  // The user's text (template, path or URL): messages and dataset.json's sources.
  const std::string& name() const { return name_; }
  virtual const char* kind() const = 0;  // "tile directory", "tile URL", "MBTiles", "PMTiles"
  virtual XyzSourceExtent extent() const = 0;
  // False for URL templates: tilesAt() then lists every tile over the bounds, existing or not.
  virtual bool listsTiles() const = 0;
  // True when reads go over the network (URL templates, PMTiles by URL): worth more workers
  // than cores, since they mostly wait.
  virtual bool remote() const { return false; }

  // The tiles at zoom z that overlap `bounds` (all of them when nullopt), sorted. A URL
  // template needs bounds (InvalidInput without), and refuses more than maxTiles candidates.
  virtual Result<std::vector<geo::TileId>> tilesAt(int z, const std::optional<geo::GeoBounds>& bounds,
                                                   uint64_t maxTiles) = 0;
  // The tile's encoded bytes; nullopt when the source has no tile there.
  virtual Result<std::optional<std::vector<uint8_t>>> read(const geo::TileId& id) = 0;
  // How messages name one tile: its path or URL, or "ARCHIVE tile z/x/y".
  virtual std::string tileName(const geo::TileId& id) const = 0;

 protected:
  explicit XyzSource(std::string name) : name_(std::move(name)) {}

 private:
  std::string name_;
};

// Opens the source `text` names (see above); archives are opened and checked here (header,
// metadata), so a corrupt or missing archive is an error naming it before anything is written.
Result<std::unique_ptr<XyzSource>> openXyzSource(const std::string& text, const HttpFetchOptions& http = {});

// The kinds, for openXyzSource and tests.
Result<std::unique_ptr<XyzSource>> openTileDirectorySource(const std::string& pathTemplate);
Result<std::unique_ptr<XyzSource>> openTileUrlSource(const std::string& urlTemplate, const HttpFetchOptions& http);
Result<std::unique_ptr<XyzSource>> openMbtilesSource(const std::filesystem::path& file);
Result<std::unique_ptr<XyzSource>> openPmtilesSource(const std::string& pathOrUrl, const HttpFetchOptions& http);

// A local archive's first check, `named` as messages name it: NotFound "<named> does not exist",
// InvalidInput "<named> is not a file" (a directory, a FIFO, a device).
Status checkArchiveFile(const std::filesystem::path& file, const std::string& named);

// The tiles that match a path template, sorted (the directory source's listing).
struct XyzTileFile {
  geo::TileId id;
  std::filesystem::path path;
};
Result<std::vector<XyzTileFile>> findXyzTiles(const std::string& pathTemplate);

// Reads a whole local tile file (a regular file of at most maxBytes); nullopt when there is none.
Result<std::optional<std::vector<uint8_t>>> readTileFile(const std::filesystem::path& path,
                                                         uint64_t maxBytes = 64ull << 20);

}  // namespace vegstream::datasets
