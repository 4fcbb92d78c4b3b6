// Tiles in a local directory named by a path template (xyz_source.h): the files are found by
// walking the directory below the template's fixed prefix and matching the rest as a regular
// expression; {-y} rows are flipped to XYZ rows (tile_template.h).

#include <algorithm>
#include <limits>
#include <map>
#include <regex>
#include <system_error>

#include "core/regular_file.h"
#include "datasets/message.h"
#include "datasets/tile_template.h"
#include "datasets/xyz_source.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

std::string regexEscape(char c) {
  static const std::string special = R"(\^$.|?*+()[]{}/)";
  return special.find(c) != std::string::npos ? std::string{'\\', c} : std::string(1, c);
}

class TileDirectorySource final : public XyzSource {
 public:
  TileDirectorySource(TileTemplate tmpl, std::vector<XyzTileFile> files)
      : XyzSource(tmpl.text), tmpl_(std::move(tmpl)), files_(std::move(files)) {
    for (const auto& f : files_) pathOf_.emplace(f.id, f.path);
  }
  const char* kind() const override { return "tile directory"; }
  bool listsTiles() const override { return true; }
  XyzSourceExtent extent() const override {
    XyzSourceExtent e;
    if (!files_.empty()) e.minZoom = files_.front().id.z, e.maxZoom = files_.back().id.z;
    return e;
  }
  Result<std::vector<geo::TileId>> tilesAt(int z, const std::optional<geo::GeoBounds>& bounds, uint64_t) override {
    const auto ranges = bounds ? geo::tileRangesCovering(*bounds, z) : std::vector<geo::TileRange>{};
    std::vector<geo::TileId> ids;
    for (const auto& f : files_) {
      if (f.id.z != z) continue;
      if (bounds && std::none_of(ranges.begin(), ranges.end(), [&](const auto& r) { return r.contains(f.id); }))
        continue;
      ids.push_back(f.id);
    }
    return ids;
  }
  // The file the listing found (names such as "0758.png" match too), else none.
  Result<std::optional<std::vector<uint8_t>>> read(const geo::TileId& id) override {
    const auto it = pathOf_.find(id);
    if (it == pathOf_.end()) return std::optional<std::vector<uint8_t>>();
    return readTileFile(it->second);
  }
  std::string tileName(const geo::TileId& id) const override {
    const auto it = pathOf_.find(id);
    return it == pathOf_.end() ? expandTileTemplate(tmpl_, id) : it->second.string();
  }

 private:
  TileTemplate tmpl_;
  std::vector<XyzTileFile> files_;
  std::map<geo::TileId, fs::path> pathOf_;
};

}  // namespace

Result<std::optional<std::vector<uint8_t>>> readTileFile(const fs::path& path, uint64_t maxBytes) {
  // The checked opener (core/regular_file.h): only a regular file, at most maxBytes.
  auto bytes = readRegularFileBytes(path, FileCeiling{"a source tile", maxBytes});
  if (!bytes && bytes.error().kind == ErrorKind::NotFound) return std::optional<std::vector<uint8_t>>();
  if (!bytes) return bytes.error();
  return std::optional<std::vector<uint8_t>>(std::move(*bytes));
}

Result<std::vector<XyzTileFile>> findXyzTiles(const std::string& text) {
  auto tmpl = parseTileTemplate(text);
  if (!tmpl) return tmpl.error();
  // The fixed directory before the first placeholder; the rest becomes a regular expression.
  const size_t firstBrace = text.find('{');
  const size_t slash = text.rfind('/', firstBrace);
  const fs::path root(slash == std::string::npos ? std::string(".") : text.substr(0, slash + 1));
  const std::string rest = slash == std::string::npos ? text : text.substr(slash + 1);
  std::error_code ec;
  if (!fs::is_directory(root, ec))
    return makeError(ErrorKind::NotFound, concat("tile template '", text, "': directory ", root, " does not exist"));

  std::string pattern;
  std::vector<char> order;  // which group is z, x, y ('y' also for {-y})
  for (size_t i = 0; i < rest.size();) {
    const bool tms = rest.compare(i, 4, "{-y}") == 0;
    if (tms || rest.compare(i, 3, "{z}") == 0 || rest.compare(i, 3, "{x}") == 0 || rest.compare(i, 3, "{y}") == 0) {
      order.push_back(tms ? 'y' : rest[i + 1]);
      pattern += "(\\d{1,10})";
      i += tms ? 4 : 3;
    } else {
      pattern += regexEscape(rest[i++]);
    }
  }
  const std::regex re(pattern);
  const int maxDepth = static_cast<int>(std::count(rest.begin(), rest.end(), '/'));

  std::vector<XyzTileFile> files;
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::skip_permission_denied, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it.depth() >= maxDepth) it.disable_recursion_pending();
    if (!it->is_regular_file(ec)) continue;
    const std::string rel = it->path().lexically_relative(root).generic_string();
    std::smatch m;
    if (!std::regex_match(rel, m, re)) continue;
    geo::TileId id;
    for (size_t g = 0; g < 3; ++g) {
      const long long v = std::stoll(m[g + 1].str());
      if (v > std::numeric_limits<int>::max())
        return makeError(ErrorKind::InvalidInput,
                         concat("tile template '", text, "' matches ", it->path(), ", whose numbers are out of range"));
      (order[g] == 'z' ? id.z : order[g] == 'x' ? id.x : id.y) = static_cast<int>(v);
    }
    const bool zoomOk = id.z >= 0 && id.z <= geo::kMaxTileZoom;
    if (zoomOk && tmpl->tmsRows) id.y = flipTileRow(id.y, id.z);
    if (!zoomOk || !geo::isValid(id))
      return makeError(ErrorKind::InvalidInput, concat("tile ", it->path(), " is not a valid ",
                                                       tmpl->tmsRows ? "TMS" : "XYZ", " tile (", m[0].str(), ")"));
    files.push_back({id, it->path()});
  }
  if (ec) return makeError(ErrorKind::Io, concat("cannot list ", root, ": ", ec.message()));
  std::sort(files.begin(), files.end(), [](const XyzTileFile& a, const XyzTileFile& b) { return a.id < b.id; });
  for (size_t i = 1; i < files.size(); ++i)
    if (files[i].id == files[i - 1].id)  // "758.png" and "0758.png"
      return makeError(ErrorKind::InvalidInput, concat("tile template '", text, "': ", files[i - 1].path, " and ",
                                                       files[i].path, " are both tile ", geo::toString(files[i].id)));
  return files;
}

Result<std::unique_ptr<XyzSource>> openTileDirectorySource(const std::string& pathTemplate) {
  auto tmpl = parseTileTemplate(pathTemplate);
  if (!tmpl) return tmpl.error();
  auto files = findXyzTiles(pathTemplate);
  if (!files) return files.error();
  return std::unique_ptr<XyzSource>(new TileDirectorySource(std::move(*tmpl), std::move(*files)));
}

}  // namespace vegstream::datasets
