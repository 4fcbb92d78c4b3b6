// Which kind of tile source a text names (xyz_source.h), and the URL template source: tiles
// asked for one by one over HTTP(S) (http_fetch.h); 404 / 410 = no tile there.

#include "datasets/xyz_source.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "core/regular_file.h"
#include "datasets/message.h"
#include "datasets/tile_template.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

class TileUrlSource final : public XyzSource {
 public:
  TileUrlSource(TileTemplate tmpl, const HttpFetchOptions& http)
      : XyzSource(tmpl.text), tmpl_(std::move(tmpl)), http_(http) {}
  const char* kind() const override { return "tile URL"; }
  bool listsTiles() const override { return false; }
  bool remote() const override { return true; }
  XyzSourceExtent extent() const override { return {}; }
  Result<std::vector<geo::TileId>> tilesAt(int z, const std::optional<geo::GeoBounds>& bounds,
                                           uint64_t maxTiles) override {
    if (!bounds)
      return makeError(ErrorKind::InvalidInput,
                       concat("tile URL '", name(), "' cannot be listed: give the area with --bounds W,S,E,N"));
    uint64_t count = 0;
    for (const auto& r : geo::tileRangesCovering(*bounds, z)) count += static_cast<uint64_t>(r.count());
    if (count > maxTiles)
      return makeError(ErrorKind::InvalidInput,
                       concat("tile URL '", name(), "': the bounds hold ", count, " tiles at zoom ", z, "; at most ",
                              maxTiles, " are imported (a smaller --bounds or a lower --max-zoom)"));
    auto ids = geo::tilesCovering(*bounds, z);
    std::sort(ids.begin(), ids.end());
    return ids;
  }
  Result<std::optional<std::vector<uint8_t>>> read(const geo::TileId& id) override {
    return http_.get(expandTileTemplate(tmpl_, id));
  }
  std::string tileName(const geo::TileId& id) const override { return expandTileTemplate(tmpl_, id); }

 private:
  TileTemplate tmpl_;
  HttpFetcher http_;
};

bool endsWith(const std::string& s, const char* suffix) {
  const size_t n = std::strlen(suffix);
  if (s.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suffix[i]) return false;
  return true;
}

// The first 16 bytes of a local file (fewer when it is shorter), through the checked opener: a
// directory, FIFO or device is an error naming it (core/regular_file.h), never a hang.
Result<std::string> firstBytes(const fs::path& path) { return readRegularFileHead(path, 16); }

}  // namespace

Result<std::unique_ptr<XyzSource>> openTileUrlSource(const std::string& urlTemplate, const HttpFetchOptions& http) {
  auto tmpl = parseTileTemplate(urlTemplate);
  if (!tmpl) return tmpl.error();
  if (!tmpl->isUrl)
    return makeError(ErrorKind::InvalidInput, concat("'", urlTemplate, "' is not an http:// or https:// URL"));
  return std::unique_ptr<XyzSource>(new TileUrlSource(std::move(*tmpl), http));
}

Status checkArchiveFile(const fs::path& file, const std::string& named) {
  std::error_code ec;
  const auto status = fs::status(file, ec);
  if (status.type() == fs::file_type::not_found) return makeError(ErrorKind::NotFound, named + " does not exist");
  if (!fs::is_regular_file(status)) return makeError(ErrorKind::InvalidInput, named + " is not a file");
  return {};
}

Result<std::unique_ptr<XyzSource>> openXyzSource(const std::string& text, const HttpFetchOptions& http) {
  if (text.empty()) return makeError(ErrorKind::InvalidInput, "empty tile source");
  const bool url = looksLikeHttpUrl(text);
  // Anything with a placeholder is a template (bad ones are refused by parseTileTemplate).
  if (text.find('{') != std::string::npos) return url ? openTileUrlSource(text, http) : openTileDirectorySource(text);
  std::string bare = text.substr(0, text.find_first_of(url ? "?#" : ""));
  if (endsWith(bare, ".pmtiles")) return openPmtilesSource(text, http);
  if (url)
    return makeError(ErrorKind::Unsupported,
                     concat("'", text,
                            "': over HTTP vegstream reads tile URL templates (…/{z}/{x}/{y}.png) and "
                            ".pmtiles archives; MBTiles must be a local file"));
  if (endsWith(bare, ".mbtiles")) return openMbtilesSource(text);
  std::error_code ec;
  if (!fs::exists(text, ec))
    return makeError(ErrorKind::NotFound, concat("tile source '", text,
                                                 "' does not exist (expected a template "
                                                 "DIR/{z}/{x}/{y}.png, an .mbtiles or a "
                                                 ".pmtiles file)"));
  const auto firstSixteen = firstBytes(text);
  if (!firstSixteen) return firstSixteen.error();
  const std::string& head = *firstSixteen;
  if (head.rfind("SQLite format 3", 0) == 0) return openMbtilesSource(text);
  if (head.rfind("PMTiles", 0) == 0) return openPmtilesSource(text, http);
  return makeError(ErrorKind::InvalidInput,
                   concat("tile source '", text,
                          "' is neither a template with {z}/{x}/{y}, an MBTiles (SQLite) nor a "
                          "PMTiles archive"));
}

}  // namespace vegstream::datasets
