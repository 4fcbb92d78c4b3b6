// The canopy layer of a GDAL import (canopy_import.h): open and check the CHM, its tiles at its
// own zoom, the pyramid of highest heights below.

#include "datasets/canopy_import.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <set>
#include <vector>

#include "core/parallel_for.h"
#include "datasets/canopy.h"
#include "datasets/dataset_finish.h"
#include "datasets/geotiff_import.h"
#include "datasets/message.h"

namespace vegstream::datasets {
namespace fs = std::filesystem;

namespace {

geo::GeoBounds intersection(const geo::GeoBounds& a, const geo::GeoBounds& b) {
  return {std::max(a.westDeg, b.westDeg), std::max(a.southDeg, b.southDeg), std::min(a.eastDeg, b.eastDeg),
          std::min(a.northDeg, b.northDeg)};
}

// One tile at the layer's zoom; `wrote` when any pixel has a height.
Status writeCanopyAt(const fs::path& dir, const geo::TileId& id, const SourceGrid& grid, bool& wrote, uint64_t& bytes) {
  const auto px = grid.tilePixelsToSource(id, kTileSize);
  auto window = grid.windowFor(px, 2, kMaxWindowSide);
  if (!window) return window.error();
  if (!*window) return {};
  if (auto s = checkCanopyRaster(**window); !s) return s;
  CanopyTile t;
  t.id = id;
  t.decimetres.resize(px.size());
  for (size_t i = 0; i < px.size(); ++i) {
    t.decimetres[i] = canopyCodeOf(sampleValue(**window, px[i]));
    wrote = wrote || t.decimetres[i] != kNoCanopy;
  }
  if (!wrote) return {};
  const fs::path p = canopyTilePath(dir, id);
  if (auto s = writeCanopyTile(p, t); !s) return s;
  bytes = fileBytes(p);
  return {};
}

// The parent of up to four children: each pixel the highest valid of its 2 × 2.
Result<std::optional<CanopyTile>> reduceCanopy(const fs::path& dir, const geo::TileId& parent,
                                               const std::set<geo::TileId>& present) {
  const int n = kTileSize, half = n / 2;
  CanopyTile out;
  out.id = parent;
  out.decimetres.assign(size_t(n) * size_t(n), kNoCanopy);
  bool any = false;
  for (int k = 0; k < 4; ++k) {
    const geo::TileId child{parent.z + 1, parent.x * 2 + (k & 1), parent.y * 2 + (k >> 1)};
    if (!present.count(child)) continue;
    auto c = readCanopyTile(canopyTilePath(dir, child), child);
    if (!c) return c.error();
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const uint16_t v = c->at(x, y);
        if (v == kNoCanopy) continue;
        uint16_t& o = out.decimetres[size_t((k >> 1) * half + y / 2) * size_t(n) + size_t((k & 1) * half + x / 2)];
        o = o == kNoCanopy ? v : std::max(o, v);
        any = true;
      }
  }
  if (!any) return std::optional<CanopyTile>();
  return std::optional<CanopyTile>(std::move(out));
}

Status buildCanopyPyramid(const fs::path& dir, std::set<geo::TileId> level, int fromZoom, int toZoom, int threads,
                          TaskRunner* tasks, DatasetMeta& meta) {
  for (int z = fromZoom - 1; z >= toZoom; --z) {
    std::set<geo::TileId> parentSet;
    for (const geo::TileId& t : level) parentSet.insert(geo::parent(t));
    const std::vector<geo::TileId> parents(parentSet.begin(), parentSet.end());
    std::vector<uint64_t> bytes(parents.size(), 0);
    Status s = parallelFor(parents.size(), threads, tasks, [&](size_t i) -> Status {
      auto t = reduceCanopy(dir, parents[i], level);
      if (!t) return t.error();
      if (!*t) return {};
      const fs::path p = canopyTilePath(dir, parents[i]);
      if (auto w = writeCanopyTile(p, **t); !w) return w;
      bytes[i] = std::max<uint64_t>(1, fileBytes(p));
      return {};
    });
    if (!s) return s;
    level.clear();
    for (size_t i = 0; i < parents.size(); ++i)
      if (bytes[i]) {
        level.insert(parents[i]);
        ++meta.canopyTiles;
        meta.bytes += bytes[i];
      }
  }
  return {};
}

}  // namespace

Result<CanopyLayer> openCanopy(const std::string& file, const std::optional<geo::Crs>& crs, const SourceGrid& dem,
                               uint64_t overviewPixels, const Logger& log) {
  // heights: scale / offset applied, a declared foot unit converted to metres.
  auto opened = openGridded(
      file,
      {.flag = "--canopy-height", .crsFlag = "--canopy-height-crs", .assumeCrs = crs, .bands = {1}, .heights = true});
  if (!opened) return opened.error();
  CanopyLayer l{file, opened->source, opened->grid};
  if (!extentsOverlap(dem.extent(), l.grid->extent()))
    return makeError(ErrorKind::InvalidInput,
                     concat("the canopy height model ", file, " (", extentText(l.grid->extent()), ") and the DEM (",
                            extentText(dem.extent()), ") do not overlap"));
  auto overview = l.source->readOverview(overviewPixels);
  if (!overview) return overview.error();
  if (auto s = checkCanopyRaster(*overview); !s) return s.error();
  const double lat = intersection(dem.extent(), l.grid->extent()).centre().y;
  l.zoom = naturalZoom(l.grid->pixelSizeM(), lat);
  if (l.source->verticalScale() != 1.0)
    log->info("{}: heights in a declared unit of {} m, converted to metres", file, l.source->verticalScale());
  log->info("{}: canopy heights, {} ({:.2f} m pixels) → zoom {}", file, l.grid->crs().name(), l.grid->pixelSizeM(),
            l.zoom);
  return l;
}

Status importCanopyTiles(const fs::path& dir, const CanopyLayer& layer, const geo::GeoBounds& demExtent,
                         uint64_t maxTiles, int threads, TaskRunner* tasks, ProgressSink& progress, DatasetMeta& meta) {
  const geo::GeoBounds area = intersection(demExtent, layer.grid->extent());
  uint64_t count = 0;
  for (const auto& r : geo::tileRangesCovering(area, layer.zoom)) count += static_cast<uint64_t>(r.count());
  if (count > maxTiles)
    return makeError(ErrorKind::InvalidInput, concat("the canopy height model ", layer.file, " at zoom ", layer.zoom,
                                                     " needs ", count, " tiles, more than the limit of ", maxTiles));
  const std::vector<geo::TileId> tiles = geo::tilesCovering(area, layer.zoom);
  progress.addTotal(tiles.size());
  progress.stage(concat("canopy, zoom ", layer.zoom));
  std::vector<uint64_t> bytes(tiles.size(), 0);
  Status s = parallelFor(tiles.size(), threads, tasks, [&](size_t i) -> Status {
    bool wrote = false;
    if (auto w = writeCanopyAt(dir, tiles[i], *layer.grid, wrote, bytes[i]); !w) return w;
    if (wrote) bytes[i] = std::max<uint64_t>(bytes[i], 1);
    progress.tileDone(bytes[i]);
    return {};
  });
  if (!s) return s;
  std::set<geo::TileId> level;
  for (size_t i = 0; i < tiles.size(); ++i)
    if (bytes[i]) {
      level.insert(tiles[i]);
      ++meta.canopyTiles;
      meta.bytes += bytes[i];
    }
  if (level.empty())
    return makeError(ErrorKind::InvalidInput, concat("the canopy height model ", layer.file,
                                                     " has no height over the DEM (all nodata where they overlap)"));
  meta.canopyZoom = layer.zoom;
  return buildCanopyPyramid(dir, std::move(level), layer.zoom, std::min(meta.minZoom, layer.zoom), threads, tasks,
                            meta);
}

}  // namespace vegstream::datasets
