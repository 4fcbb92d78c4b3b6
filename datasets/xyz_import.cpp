// Import of existing XYZ elevation (+ imagery) tiles into a dataset directory (xyz_import.h).
// The source tiles are decoded (which also validates them) and re-encoded, so the dataset's
// tiles are always RGBA PNG / JPEG in the encodings dataset.json states.

#include "datasets/xyz_import.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <regex>
#include <system_error>

#include "core/atomic_file.h"
#include "datasets/dataset_finish.h"
#include "datasets/message.h"
#include "core/parallel_for.h"
#include "datasets/tile_codec.h"
#include "geo/crs.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

std::string regexEscape(const std::string& s) {
  static const std::string special = R"(\^$.|?*+()[]{}/)";
  std::string out;
  for (char c : s) {
    if (special.find(c) != std::string::npos) out += '\\';
    out += c;
  }
  return out;
}

Error badTemplate(const std::string& tmpl, const std::string& problem) {
  return makeError(ErrorKind::InvalidInput, concat("tile template '", tmpl, "' ", problem));
}

// "[z a … b]" of a tile list, for messages.
std::string zoomsOf(const std::vector<XyzTileFile>& files) {
  std::map<int, size_t> zooms;
  for (const auto& f : files) ++zooms[f.id.z];
  std::string s;
  for (const auto& [z, n] : zooms) {
    if (!s.empty()) s += ", ";
    s += concat(n, " at zoom ", z);
  }
  return s;
}

std::vector<XyzTileFile> atZoom(const std::vector<XyzTileFile>& files, int z) {
  std::vector<XyzTileFile> out;
  std::copy_if(files.begin(), files.end(), std::back_inserter(out), [z](const XyzTileFile& f) { return f.id.z == z; });
  return out;
}

}  // namespace

Result<std::vector<XyzTileFile>> findXyzTiles(const std::string& tmpl) {
  for (const char* key : {"{z}", "{x}", "{y}"}) {
    const size_t first = tmpl.find(key);
    if (first == std::string::npos)
      return badTemplate(tmpl, concat("has no ", key, "; expected e.g. DIR/{z}/{x}/{y}.png"));
    if (tmpl.find(key, first + 1) != std::string::npos) return badTemplate(tmpl, concat("has ", key, " twice"));
  }
  if (tmpl.find("{-y}") != std::string::npos) return badTemplate(tmpl, "uses {-y} (TMS rows), which is not supported");
  // The fixed directory before the first placeholder; the rest becomes a regular expression.
  const size_t firstBrace = tmpl.find('{');
  const size_t slash = tmpl.rfind('/', firstBrace);
  const std::string rootText = slash == std::string::npos ? std::string(".") : tmpl.substr(0, slash + 1);
  const std::string rest = slash == std::string::npos ? tmpl : tmpl.substr(slash + 1);
  const fs::path root(rootText);
  std::error_code ec;
  if (!fs::is_directory(root, ec))
    return makeError(ErrorKind::NotFound, concat("tile template '", tmpl, "': directory ", root, " does not exist"));

  std::string pattern;
  std::vector<char> order;  // which group is z, x, y
  for (size_t i = 0; i < rest.size();) {
    if (rest.compare(i, 3, "{z}") == 0 || rest.compare(i, 3, "{x}") == 0 || rest.compare(i, 3, "{y}") == 0) {
      order.push_back(rest[i + 1]);
      pattern += "(\\d{1,10})";
      i += 3;
    } else {
      pattern += regexEscape(std::string(1, rest[i]));
      ++i;
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
        return badTemplate(tmpl, concat("matches ", it->path(), ", whose numbers are out of range"));
      (order[g] == 'z' ? id.z : order[g] == 'x' ? id.x : id.y) = static_cast<int>(v);
    }
    if (id.z > geo::kMaxTileZoom || !geo::isValid(id))
      return makeError(ErrorKind::InvalidInput,
                       concat("tile ", it->path(), " is not a valid XYZ tile (", geo::toString(id), ")"));
    files.push_back({id, it->path()});
  }
  if (ec) return makeError(ErrorKind::Io, concat("cannot list ", root, ": ", ec.message()));
  std::sort(files.begin(), files.end(), [](const XyzTileFile& a, const XyzTileFile& b) { return a.id < b.id; });
  return files;
}

Result<DatasetMeta> importXyzTiles(const XyzImportOptions& options, const Logger& log, const XyzProgress& progress) {
  if (!progress) {
    NullProgress none;
    return importXyzTiles(options, log, none);
  }
  CallbackProgress sink(progress);
  return importXyzTiles(options, log, sink);
}

Result<DatasetMeta> importXyzTiles(const XyzImportOptions& options, const Logger& log, ProgressSink& progress) {
  assert(!options.out.empty());
  auto elevationFiles = findXyzTiles(options.elevationTemplate);
  if (!elevationFiles) return elevationFiles.error();
  if (elevationFiles->empty())
    return makeError(ErrorKind::InvalidInput, concat("no elevation tiles match '", options.elevationTemplate, "'"));
  const int maxZoom = elevationFiles->back().id.z;
  const std::vector<XyzTileFile> elevation = atZoom(*elevationFiles, maxZoom);
  if (elevation.size() != elevationFiles->size())
    log->info("elevation tiles found: {}; zooms below {} are rebuilt from zoom {}", zoomsOf(*elevationFiles), maxZoom,
              maxZoom);

  std::vector<XyzTileFile> imagery;
  if (options.imageryTemplate) {
    auto files = findXyzTiles(*options.imageryTemplate);
    if (!files) return files.error();
    imagery = atZoom(*files, maxZoom);
    if (imagery.empty())
      return makeError(
          ErrorKind::InvalidInput,
          concat("no imagery tiles at zoom ", maxZoom, " (the elevation's finest zoom) match '",
                 *options.imageryTemplate, "'", files->empty() ? std::string() : concat("; found ", zoomsOf(*files))));
    if (imagery.size() != files->size())
      log->warn("imagery tiles found: {}; only zoom {} is imported", zoomsOf(*files), maxZoom);
  }

  std::vector<geo::TileId> ids;
  for (const auto& f : elevation) ids.push_back(f.id);
  DatasetMeta meta;
  meta.name = options.name.empty() ? defaultDatasetName(options.out) : options.name;
  meta.maxZoom = maxZoom;
  meta.minZoom = options.minZoom ? std::clamp(*options.minZoom, 0, maxZoom) : singleTileZoom(ids);
  meta.elevationEncoding = options.outputEncoding.value_or(options.encoding);
  if (!imagery.empty()) meta.imagery = options.imageryFormat;
  meta.attribution = options.attribution;
  meta.bounds = geo::tileBoundsLonLat(ids.front());
  for (const auto& id : ids) {
    const geo::GeoBounds b = geo::tileBoundsLonLat(id);
    meta.bounds.westDeg = std::min(meta.bounds.westDeg, b.westDeg);
    meta.bounds.eastDeg = std::max(meta.bounds.eastDeg, b.eastDeg);
    meta.bounds.southDeg = std::min(meta.bounds.southDeg, b.southDeg);
    meta.bounds.northDeg = std::max(meta.bounds.northDeg, b.northDeg);
  }
  const std::string crs = geo::webMercatorCrs().name();
  meta.sources.push_back({"elevation", options.elevationTemplate, crs,
                          concat(elevation.size(), " ", toString(options.encoding), " tiles at zoom ", maxZoom)});
  if (!imagery.empty())
    meta.sources.push_back(
        {"imagery", *options.imageryTemplate, crs, concat(imagery.size(), " tiles at zoom ", maxZoom)});

  Result<DatasetMeta> result = meta;
  Status status = writeDirectoryAtomically(options.out, [&](const fs::path& tmp) -> Status {
    std::mutex mutex;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    progress.stage(concat("zoom ", maxZoom));
    progress.addTotal(elevation.size() + imagery.size());
    Status s = parallelFor(elevation.size(), options.threads, options.tasks, [&](size_t i) -> Status {
      const XyzTileFile& f = elevation[i];
      auto tile = readHeightTile(f.path, f.id, options.encoding);
      if (!tile) return tile.error();
      if (tile->size != kTileSize)
        return makeError(ErrorKind::Unsupported, concat("tile ", f.path, " is ", tile->size,
                                                        " pixels wide; vegstream reads ", kTileSize, "-pixel tiles"));
      double tlo = std::numeric_limits<double>::infinity(), thi = -tlo;
      for (float h : tile->heights)
        if (!std::isnan(h)) tlo = std::min(tlo, double{h}), thi = std::max(thi, double{h});
      const fs::path dst = elevationTilePath(tmp, f.id);
      if (auto w = writeHeightTile(dst, *tile, meta.elevationEncoding); !w) return w;
      const uint64_t bytes = fileBytes(dst);
      {
        std::lock_guard lock(mutex);
        lo = std::min(lo, tlo);
        hi = std::max(hi, thi);
        meta.bytes += bytes;
        ++meta.elevationTiles;
      }
      progress.tileDone(bytes);
      return {};
    });
    if (!s) return s;
    if (!(lo <= hi))
      return makeError(ErrorKind::InvalidInput,
                       concat("the elevation tiles of '", options.elevationTemplate, "' hold no valid heights"));
    meta.minHeightM = lo;
    meta.maxHeightM = hi;
    s = parallelFor(imagery.size(), options.threads, options.tasks, [&](size_t i) -> Status {
      const XyzTileFile& f = imagery[i];
      auto tile = readColorTile(f.path, f.id);
      if (!tile) return tile.error();
      if (tile->size != kTileSize)
        return makeError(ErrorKind::Unsupported, concat("tile ", f.path, " is ", tile->size,
                                                        " pixels wide; vegstream reads ", kTileSize, "-pixel tiles"));
      const fs::path dst = imageryTilePath(tmp, f.id, options.imageryFormat);
      if (auto w = writeColorTile(dst, *tile, options.imageryFormat, options.jpegQuality); !w) return w;
      const uint64_t bytes = fileBytes(dst);
      {
        std::lock_guard lock(mutex);
        meta.bytes += bytes;
        ++meta.imageryTiles;
      }
      progress.tileDone(bytes);
      return {};
    });
    if (!s) return s;
    result = finishDataset(tmp, meta, progress, options.threads, options.jpegQuality, options.tasks);
    return result ? Status{} : Status{result.error()};
  });
  if (!status) return status.error();
  return result;
}

}  // namespace vegstream::datasets
