// Import of existing elevation (+ imagery) tiles into a dataset directory (xyz_import.h).
// The source tiles are decoded (which also validates them), 512-pixel tiles split into four
// 256-pixel tiles (xyz_source_tiles.h), and re-encoded, so the dataset's tiles are always RGBA
// PNG / JPEG in the encodings dataset.json states, whatever kind of source they came from.

#include "datasets/xyz_import.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <set>

#include "core/atomic_file.h"
#include "core/parallel_for.h"
#include "datasets/dataset_finish.h"
#include "datasets/message.h"
#include "datasets/tile_codec.h"
#include "datasets/xyz_source_tiles.h"
#include "geo/crs.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

// One source and the tiles to read from it at one zoom.
struct SourcePlan {
  std::unique_ptr<XyzSource> source;
  int zoom = 0;
  std::vector<geo::TileId> ids;
};

// What the workers of one stage gather (under `mutex`).
struct Written {
  std::mutex mutex;
  std::vector<geo::TileId> ids;  // dataset tiles written
  uint64_t sourceTiles = 0;      // source tiles that existed
  uint64_t bytes = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  std::atomic<int> tileSize{0};  // of the source tiles: all alike
};

Status checkCancel(const XyzImportOptions& o) {
  if (o.cancel && o.cancel->load())
    return makeError(ErrorKind::InvalidInput, "import interrupted; nothing was written");
  return {};
}

// Workers for one source: the option, else all cores — at least remoteWorkers over the network.
int workersFor(const XyzImportOptions& o, const XyzSource& source) {
  if (o.threads != 0 || !source.remote()) return o.threads;
  return std::max(resolveThreads(0), o.remoteWorkers);
}

Status sameSize(Written& w, const XyzSource& source, const geo::TileId& id, int size) {
  int expected = 0;
  if (w.tileSize.compare_exchange_strong(expected, size) || expected == size) return {};
  return makeError(ErrorKind::InvalidInput, concat("tile '", source.tileName(id), "' is ", size,
                                                   " pixels wide, other tiles of the same source ", expected));
}

Result<SourcePlan> planElevation(const XyzImportOptions& o) {
  SourcePlan plan;
  auto source = openXyzSource(o.elevationTemplate, o.http);
  if (!source) return source.error();
  plan.source = std::move(*source);
  const XyzSourceExtent extent = plan.source->extent();
  const auto zoom = o.maxZoom ? o.maxZoom : extent.maxZoom;
  const auto bounds = o.bounds ? o.bounds : extent.bounds;
  if (!plan.source->listsTiles() && (!zoom || !bounds))
    return makeError(ErrorKind::InvalidInput,
                     concat("tile URL '", plan.source->name(),
                            "' cannot be listed: give the area and the zoom with --bounds W,S,E,N and --max-zoom Z"));
  if (!zoom)
    return makeError(ErrorKind::InvalidInput,
                     concat("no elevation tiles in ", plan.source->kind(), " '", plan.source->name(), "'"));
  plan.zoom = *zoom;
  auto ids = plan.source->tilesAt(plan.zoom, bounds, o.maxTiles);
  if (!ids) return ids.error();
  if (ids->empty())
    return makeError(ErrorKind::InvalidInput,
                     concat("no elevation tiles at zoom ", plan.zoom, o.bounds ? " over --bounds" : "", " in ",
                            plan.source->kind(), " '", plan.source->name(), "'"));
  plan.ids = std::move(*ids);
  // The first tile asked for before anything is written or reported: a server that does not
  // answer, or a corrupt first tile, ends the import with its one message.
  auto first = probeSourceTileSize(*plan.source, {plan.ids.front()});
  if (!first) return first.error();
  return plan;
}

// The imagery source, opened (an archive's header and metadata checked) and asked for one tile
// before anything is written or reported, like the elevation's.
Result<std::unique_ptr<XyzSource>> openImagery(const XyzImportOptions& o, const geo::TileId& first) {
  auto source = openXyzSource(*o.imageryTemplate, o.http);
  if (!source) return source.error();
  if (auto r = (*source)->read(first); !r) return r.error();
  return std::move(*source);
}

// Imagery for the elevation tiles `written` (sorted, zoom `z`): 256-pixel tiles at z, else
// 512-pixel tiles at z − 1.
Result<SourcePlan> planImagery(std::unique_ptr<XyzSource> source, const std::vector<geo::TileId>& written, int z) {
  SourcePlan plan;
  plan.source = std::move(source);
  auto size = probeSourceTileSize(*plan.source, written);
  if (!size) return size.error();
  if (*size == kTileSize) {
    plan.zoom = z;
    plan.ids = written;
    return plan;
  }
  std::set<geo::TileId> parents;
  if (z > 0)
    for (const auto& id : written) parents.insert(geo::parent(id));
  plan.ids.assign(parents.begin(), parents.end());
  auto large = probeSourceTileSize(*plan.source, plan.ids);
  if (!large) return large.error();
  if (*large == kLargeSourceTileSize) {
    plan.zoom = z - 1;
    return plan;
  }
  return makeError(ErrorKind::InvalidInput,
                   concat("no imagery tiles over the elevation tiles in ", plan.source->kind(), " '",
                          plan.source->name(), "': needed 256-pixel tiles at zoom ", z, " or 512-pixel tiles at zoom ",
                          z - 1, *size ? " (found 512-pixel tiles at zoom " : "",
                          *size ? std::to_string(z) : std::string(), *size ? ")" : ""));
}

// A dataset tile written: where, and the range of its heights (empty for imagery).
struct TileWritten {
  fs::path path;
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
};

// Writes one layer, each source tile of the plan on the workers: read(sourceId) gives its
// dataset tiles (4 for a 512-pixel source tile, none where the source has none), and write(tile)
// writes each one kept (a TileWritten), or returns nullopt for one not kept. What was written is
// added to w.
template <class Tile, class Read, class Write>
Status writeLayer(const XyzImportOptions& o, SourcePlan& plan, ProgressSink& progress, Written& w, Read&& read,
                  Write&& write) {
  progress.addTotal(plan.ids.size());
  return parallelFor(plan.ids.size(), workersFor(o, *plan.source), o.tasks, [&](size_t i) -> Status {
    if (auto c = checkCancel(o); !c) return c;
    Result<std::vector<Tile>> tiles = read(plan.ids[i]);
    if (!tiles) return tiles.error();
    const int size = tiles->size() == 4 ? kLargeSourceTileSize : kTileSize;
    if (auto s = tiles->empty() ? Status{} : sameSize(w, *plan.source, plan.ids[i], size); !s) return s;
    uint64_t bytes = 0;
    for (const Tile& t : *tiles) {
      Result<std::optional<TileWritten>> written = write(t);
      if (!written) return written.error();
      if (!*written) continue;
      const uint64_t b = fileBytes((*written)->path);
      bytes += b;
      std::lock_guard lock(w.mutex);
      w.lo = std::min(w.lo, (*written)->lo), w.hi = std::max(w.hi, (*written)->hi);
      w.ids.push_back(t.id);
      w.bytes += b;
    }
    if (!tiles->empty()) {
      std::lock_guard lock(w.mutex);
      ++w.sourceTiles;
    }
    progress.tileDone(bytes);
    return {};
  });
}

Status writeElevation(const XyzImportOptions& o, SourcePlan& plan, ElevationEncoding encoding, const fs::path& tmp,
                      ProgressSink& progress, Written& w) {
  progress.stage(concat("elevation, source zoom ", plan.zoom));
  return writeLayer<HeightTile>(
      o, plan, progress, w, [&](const geo::TileId& id) { return readSourceHeightTiles(*plan.source, id, o.encoding); },
      [&](const HeightTile& t) -> Result<std::optional<TileWritten>> {
        TileWritten out{elevationTilePath(tmp, t.id)};
        for (float h : t.heights)
          if (!std::isnan(h)) out.lo = std::min(out.lo, double{h}), out.hi = std::max(out.hi, double{h});
        if (auto s = writeHeightTile(out.path, t, encoding); !s) return s.error();
        return std::optional(std::move(out));
      });
}

// Imagery tiles over the elevation tiles `keep` only (a 512-pixel tile's other children are dropped).
Status writeImagery(const XyzImportOptions& o, SourcePlan& plan, const std::set<geo::TileId>& keep, const fs::path& tmp,
                    ProgressSink& progress, Written& w) {
  progress.stage(concat("imagery, source zoom ", plan.zoom));
  return writeLayer<ColorTile>(
      o, plan, progress, w, [&](const geo::TileId& id) { return readSourceColorTiles(*plan.source, id); },
      [&](const ColorTile& t) -> Result<std::optional<TileWritten>> {
        if (!keep.contains(t.id)) return std::optional<TileWritten>{};
        TileWritten out{imageryTilePath(tmp, t.id, o.imageryFormat)};
        if (auto s = writeColorTile(out.path, t, o.imageryFormat, o.jpegQuality); !s) return s.error();
        return std::optional(std::move(out));
      });
}

std::string describe(const Written& w, const std::string& what, const SourcePlan& plan) {
  const bool split = w.tileSize == kLargeSourceTileSize;
  return concat(w.sourceTiles, " ", what, "tiles at zoom ", plan.zoom,
                split ? concat(" (512 px, split into zoom ", plan.zoom + 1, ")") : std::string());
}

// The bounds of the tiles ids (not empty), degrees.
geo::GeoBounds boundsOfTiles(const std::vector<geo::TileId>& ids) {
  geo::GeoBounds bounds = geo::tileBoundsLonLat(ids.front());
  for (const auto& id : ids) {
    const geo::GeoBounds b = geo::tileBoundsLonLat(id);
    bounds.westDeg = std::min(bounds.westDeg, b.westDeg);
    bounds.eastDeg = std::max(bounds.eastDeg, b.eastDeg);
    bounds.southDeg = std::min(bounds.southDeg, b.southDeg);
    bounds.northDeg = std::max(bounds.northDeg, b.northDeg);
  }
  return bounds;
}

// The imagery tiles over the elevation tiles written (elevationIds), into tmp and meta.
Status addImagery(const XyzImportOptions& options, std::unique_ptr<XyzSource> source,
                  const std::vector<geo::TileId>& elevationIds, const fs::path& tmp, ProgressSink& progress,
                  const Logger& log, DatasetMeta& meta) {
  auto imagery = planImagery(std::move(source), elevationIds, meta.maxZoom);
  if (!imagery) return imagery.error();
  Written img;
  const std::set<geo::TileId> keep(elevationIds.begin(), elevationIds.end());
  if (auto s = writeImagery(options, *imagery, keep, tmp, progress, img); !s) return s;
  meta.imagery = options.imageryFormat;
  meta.imageryTiles = img.ids.size();
  meta.bytes += img.bytes;
  meta.sources.push_back(
      {"imagery", imagery->source->name(), geo::webMercatorCrs().name(), describe(img, "", *imagery)});
  if (img.ids.size() < elevationIds.size())
    log->warn("imagery: {} of the {} elevation tiles have no imagery in '{}'", elevationIds.size() - img.ids.size(),
              elevationIds.size(), imagery->source->name());
  return {};
}

}  // namespace

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
  auto elevation = planElevation(options);
  if (!elevation) return elevation.error();
  log->debug("elevation: {} tiles to read at zoom {} from {} '{}'", elevation->ids.size(), elevation->zoom,
             elevation->source->kind(), elevation->source->name());
  std::unique_ptr<XyzSource> imagerySource;
  if (options.imageryTemplate) {
    auto opened = openImagery(options, elevation->ids.front());
    if (!opened) return opened.error();
    imagerySource = std::move(*opened);
  }
  DatasetMeta meta;
  meta.name = options.name.empty() ? defaultDatasetName(options.out) : options.name;
  meta.elevationEncoding = options.outputEncoding.value_or(options.encoding);
  meta.attribution = options.attribution;
  const std::string crs = geo::webMercatorCrs().name();

  Result<DatasetMeta> result = meta;
  Status status = writeDirectoryAtomically(options.out, [&](const fs::path& tmp) -> Status {
    Written elev;
    if (auto s = writeElevation(options, *elevation, meta.elevationEncoding, tmp, progress, elev); !s) return s;
    if (elev.ids.empty())
      return makeError(ErrorKind::InvalidInput,
                       concat("none of the ", elevation->ids.size(), " elevation tiles at zoom ", elevation->zoom,
                              " exists in ", elevation->source->kind(), " '", elevation->source->name(), "'"));
    if (!(elev.lo <= elev.hi))
      return makeError(ErrorKind::InvalidInput,
                       concat("the elevation tiles of '", options.elevationTemplate, "' hold no valid heights"));
    std::sort(elev.ids.begin(), elev.ids.end());
    meta.maxZoom = elev.ids.front().z;
    meta.minZoom = options.minZoom ? std::clamp(*options.minZoom, 0, meta.maxZoom) : singleTileZoom(elev.ids);
    meta.minHeightM = elev.lo, meta.maxHeightM = elev.hi;
    meta.elevationTiles = elev.ids.size();
    meta.bytes = elev.bytes;
    meta.bounds = boundsOfTiles(elev.ids);
    meta.sources.push_back({"elevation", elevation->source->name(), crs,
                            describe(elev, concat(toString(options.encoding), " "), *elevation)});
    if (imagerySource)
      if (auto s = addImagery(options, std::move(imagerySource), elev.ids, tmp, progress, log, meta); !s) return s;
    result = finishDataset(tmp, meta, progress, options.threads, options.jpegQuality, options.tasks);
    if (!result) return result.error();
    return checkCancel(options);
  });
  if (!status) return status.error();
  return result;
}

}  // namespace vegstream::datasets
