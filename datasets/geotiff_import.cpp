// `vegstream import --dem …` (geotiff_import.h): read and check the sources, pick the zooms,
// reproject the max zoom's tiles in parallel, then the shared finish (pyramid, dataset.json),
// all inside a temporary directory renamed into place at the end.

#include "datasets/geotiff_import.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/atomic_file.h"
#include "datasets/dataset_finish.h"
#include "datasets/deshading_plan.h"
#include "datasets/imagery_tiles.h"
#include "datasets/message.h"
#include "core/parallel_for.h"
#include "datasets/source_grid.h"
#include "datasets/tile_codec.h"
#include "geo/projection.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

// What one max-zoom tile produced.
struct TileOutcome {
  bool elevation = false, imagery = false, ndvi = false;
  float minH = std::numeric_limits<float>::infinity(), maxH = -std::numeric_limits<float>::infinity();
  uint64_t bytes = 0;
};

struct Sources {
  const SourceGrid& dem;
  const ImageryTiling* imagery;  // null: no imagery
  const Raster* ndvi;            // on the imagery's grid (ndvi_source.h); null: no NDVI layer
};

// A max-zoom tile's heights (kTileSize², NaN = nodata).
std::vector<float> tileHeights(const SourceGrid& dem, const geo::TileId& id, HeightResampling resampling) {
  const auto demPx = dem.tilePixelsToSource(id, kTileSize);
  std::vector<float> heights(demPx.size());
  for (size_t i = 0; i < demPx.size(); ++i)
    heights[i] = resampling == HeightResampling::Cubic ? sampleHeightCubic(dem.raster(), demPx[i])
                                                       : sampleHeight(dem.raster(), demPx[i]);
  return heights;
}

Status produceTile(const fs::path& dir, const geo::TileId& id, const Sources& src, const GeoTiffImportOptions& o,
                   TileOutcome& out) {
  HeightTile h;
  h.id = id;
  h.size = kTileSize;
  h.heights = tileHeights(src.dem, id, o.heightResampling);
  for (const float v : h.heights) {
    if (!std::isfinite(v)) continue;
    out.minH = std::min(out.minH, v);
    out.maxH = std::max(out.maxH, v);
    out.elevation = true;
  }
  if (out.elevation) {
    const fs::path p = elevationTilePath(dir, id);
    if (auto s = writeHeightTile(p, h, o.encoding); !s) return s;
    out.bytes += fileBytes(p);
  }
  if (!src.imagery) return {};
  const auto imgPx = src.imagery->grid->tilePixelsToSource(id, kTileSize);
  ColorTile c;
  c.id = id;
  c.size = kTileSize;
  out.imagery = fillImageryTile(*src.imagery, imgPx, h.heights, c);
  if (out.imagery) {
    const fs::path p = imageryTilePath(dir, id, o.imageryFormat);
    if (auto s = writeColorTile(p, c, o.imageryFormat, o.jpegQuality); !s) return s;
    out.bytes += fileBytes(p);
  }
  if (!src.ndvi) return {};
  // The same source positions as the colour: NDVI lies on the imagery's grid.
  c.ndvi.assign(imgPx.size(), 0);
  for (size_t i = 0; i < imgPx.size(); ++i) {
    c.ndvi[i] = ndviToByte(sampleValue(*src.ndvi, imgPx[i]));
    out.ndvi = out.ndvi || c.ndvi[i] != 0;
  }
  if (out.ndvi) {
    const fs::path p = ndviTilePath(dir, id);
    if (auto s = writeNdviTile(p, c); !s) return s;
    out.bytes += fileBytes(p);
  }
  return {};
}

// How the tiles sample the imagery, with the sun that de-shades it (deshading_plan.h), whose
// record goes into imagery.radiometry.
Result<ImageryTiling> imageryTiling(const GeoTiffImportOptions& o, PreparedImagery& imagery, const SourceGrid& grid,
                                    const SourceGrid& dem, const std::vector<geo::TileId>& tiles, const Logger& log) {
  ImageryTiling tiling{&grid, imagery.linear, std::nullopt, o.directFraction};
  auto plan = planDeshading(
      o, imagery.radiometry, tiling, tiles, dem.extent().centre(),
      [&](const geo::TileId& id) { return tileHeights(dem, id, o.heightResampling); }, log);
  if (!plan) return plan.error();
  tiling.sun = plan->sun;
  imagery.radiometry.deshading = plan->record;
  return tiling;
}

std::string describe(const SourceGrid& g) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "%dx%d px, %.2f m pixels", g.raster().width, g.raster().height, g.pixelSizeM());
  return buf;
}

}  // namespace

int naturalZoom(double metresPerPixel, double latDeg) {
  const double z = geo::zoomForResolution(metresPerPixel, latDeg, kTileSize);
  return std::clamp(static_cast<int>(std::ceil(z - 0.1)), 0, kMaxAutoZoom);
}

Status checkOutputDirectory(const fs::path& out) {
  std::error_code ec;
  if (fs::exists(out, ec)) {
    if (!fs::is_directory(out, ec) || !fs::is_empty(out, ec))
      return makeError(
          ErrorKind::InvalidInput,
          concat("--out ", out, " already exists and is not an empty directory; choose another output directory"));
  }
  fs::path p = fs::absolute(out, ec).parent_path();
  while (!p.empty() && !fs::exists(p, ec) && p != p.parent_path()) p = p.parent_path();
  if (!fs::is_directory(p, ec))
    return makeError(ErrorKind::InvalidInput, concat("--out ", out, " cannot be created: ", p, " is not a directory"));
  if (::access(p.c_str(), W_OK | X_OK) != 0)
    return makeError(ErrorKind::InvalidInput, concat("--out ", out, " cannot be created: ", p, " is not writable"));
  return {};
}

Result<DatasetMeta> importGeoTiff(const GeoTiffImportOptions& o, const Logger& log, ProgressSink& progress) {
  if (auto s = checkOutputDirectory(o.out); !s) return s.error();
  const bool withImagery = o.imagery.file || !o.imagery.bands.empty();
  if (o.nir && !withImagery)
    return makeError(ErrorKind::InvalidInput,
                     concat("--imagery-nir ", o.nir->file,
                            " needs imagery (--imagery or --imagery-bands): NDVI is computed with the imagery's red"));
  if (!o.imageryDatetime.empty()) {
    if (auto ms = imageryUnixMs(o.imageryDatetime); !ms) return ms.error();
    if (!withImagery)
      return makeError(ErrorKind::InvalidInput,
                       "--imagery-datetime says when the imagery was taken, and no imagery was given");
  }

  // DEM.
  ReadOptions ro;
  ro.assumeEpsg = o.demEpsg;
  ro.nodataOverride = o.demNodata;
  ro.maxPixels = o.maxPixels;
  auto demRead = readGeoTiff(o.dem, ro);
  if (!demRead) return demRead.error();
  Raster& dem = *demRead;
  if (dem.channels != 1)
    return makeError(ErrorKind::InvalidInput,
                     concat(o.dem, " has ", dem.channels, " channels; a DEM has one (heights)"));
  auto demCrs = rasterCrs(dem, "--dem-crs", log);
  if (!demCrs) return demCrs.error();
  uint64_t implausible = 0, validHeights = 0;
  for (float& v : dem.samples) {
    if (dem.isNodata(v)) continue;
    if (v < kMinPlausibleHeightM || v > kMaxPlausibleHeightM) {
      v = NAN;
      ++implausible;
    } else {
      ++validHeights;
    }
  }
  if (implausible)
    log->warn("{}: {} heights outside {} … {} m treated as nodata", o.dem.string(), implausible, kMinPlausibleHeightM,
              kMaxPlausibleHeightM);
  if (validHeights == 0) return makeError(ErrorKind::InvalidInput, concat(o.dem, " has no valid height (all nodata)"));
  auto demGrid = SourceGrid::make(dem, *demCrs);
  if (!demGrid) return demGrid.error();

  // Imagery (and the NDVI on its grid).
  std::optional<PreparedImagery> imagery;
  std::optional<SourceGrid> imageryGrid;
  std::optional<NdviRaster> ndvi;
  if (withImagery) {
    ImageryInput imageryInput = o.imagery;
    imageryInput.keepRawRed = o.nir.has_value();
    auto prepared = prepareImagery(imageryInput, log);
    if (!prepared) return prepared.error();
    imagery = std::move(*prepared);
    auto crs = rasterCrs(imagery->raster, "--imagery-crs", log);
    if (!crs) return crs.error();
    auto grid = SourceGrid::make(imagery->raster, *crs);
    if (!grid) return grid.error();
    imageryGrid = std::move(*grid);
    if (!extentsOverlap(demGrid->extent(), imageryGrid->extent()))
      return makeError(ErrorKind::InvalidInput,
                       concat("the DEM ", o.dem, " (", extentText(demGrid->extent()), ") and the imagery ",
                              imagery->raster.path, " (", extentText(imageryGrid->extent()), ") do not overlap"));
    if (o.nir) {
      auto n = prepareNdvi(*o.nir, *imageryGrid, imagery->rawRed, log);
      if (!n) return n.error();
      ndvi = std::move(*n);
      imagery->rawRed = std::vector<float>();  // 4 bytes a pixel no longer needed (frees them)
    }
  }

  // Zooms and tiles.
  const geo::GeoBounds bounds = demGrid->extent();
  const double lat = bounds.centre().y;
  int maxZoom = naturalZoom(demGrid->pixelSizeM(), lat);
  if (imageryGrid) maxZoom = std::max(maxZoom, std::min(naturalZoom(imageryGrid->pixelSizeM(), lat), maxZoom + 3));
  if (o.maxZoom) maxZoom = *o.maxZoom;
  uint64_t tileCount = 0;
  for (const auto& r : geo::tileRangesCovering(bounds, maxZoom)) tileCount += static_cast<uint64_t>(r.count());
  if (tileCount > o.maxTiles)
    return makeError(ErrorKind::InvalidInput,
                     concat(o.dem, " at zoom ", maxZoom, " needs ", tileCount, " tiles, more than the limit of ",
                            o.maxTiles, "; choose a lower --max-zoom"));
  const std::vector<geo::TileId> tiles = geo::tilesCovering(bounds, maxZoom);
  log->info("{}: {} ({:.1f} m pixels) → zoom {} ({:.1f} m pixels), {} tiles", o.dem.string(), demCrs->name(),
            demGrid->pixelSizeM(), maxZoom, geo::groundResolution(lat, maxZoom, kTileSize), tiles.size());
  if (imageryGrid)
    log->info("{}: {} ({:.1f} m pixels), {}", imagery->raster.path.string(), imageryGrid->crs().name(),
              imageryGrid->pixelSizeM(), imagery->radiometryChoice);
  std::optional<ImageryTiling> tiling;
  if (imageryGrid) {
    auto t = imageryTiling(o, *imagery, *imageryGrid, *demGrid, tiles, log);
    if (!t) return t.error();
    tiling = *t;
  }

  DatasetMeta meta;
  meta.name = o.name.empty() ? defaultDatasetName(o.out) : o.name;
  meta.bounds = bounds;
  meta.maxZoom = maxZoom;
  meta.elevationEncoding = o.encoding;
  if (imageryGrid) {
    meta.imagery = o.imageryFormat;
    meta.imageryDatetime = o.imageryDatetime;
    meta.radiometry = imagery->radiometry;
  }
  meta.attribution = o.attribution;
  meta.sources.push_back({"elevation", o.dem.string(), demCrs->name(), describe(*demGrid)});
  if (imageryGrid) {
    std::string paths;
    for (const auto& b : o.imagery.bands) {
      if (!paths.empty()) paths += ',';
      paths += b.string();
    }
    if (o.imagery.file) paths = o.imagery.file->string();
    meta.sources.push_back(
        {"imagery", paths, imageryGrid->crs().name(), concat(describe(*imageryGrid), ", ", imagery->description)});
  }
  if (ndvi) {
    meta.ndvi = true;
    meta.sources.push_back({"nir", o.nir->file.string(), ndvi->nirCrs.name(), ndvi->description});
  }

  Result<DatasetMeta> result = makeError(ErrorKind::Internal, "import did not run");
  Status written = writeDirectoryAtomically(o.out, [&](const fs::path& tmp) -> Status {
    progress.addTotal(tiles.size());
    progress.stage(concat("zoom ", maxZoom));
    std::vector<TileOutcome> outcomes(tiles.size());
    const Sources src{*demGrid, tiling ? &*tiling : nullptr, ndvi ? &ndvi->raster : nullptr};
    Status s = parallelFor(tiles.size(), o.threads, o.tasks, [&](size_t i) -> Status {
      if (o.cancel && o.cancel->load())
        return makeError(ErrorKind::InvalidInput, "import interrupted; nothing was written");
      if (auto t = produceTile(tmp, tiles[i], src, o, outcomes[i]); !t) return t;
      progress.tileDone(outcomes[i].bytes);
      return {};
    });
    if (!s) return s;
    std::vector<geo::TileId> withHeights;
    meta.minHeightM = std::numeric_limits<double>::infinity();
    meta.maxHeightM = -std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < tiles.size(); ++i) {
      const TileOutcome& t = outcomes[i];
      meta.bytes += t.bytes;
      if (t.imagery) ++meta.imageryTiles;
      if (t.ndvi) ++meta.ndviTiles;
      if (!t.elevation) continue;
      ++meta.elevationTiles;
      withHeights.push_back(tiles[i]);
      meta.minHeightM = std::min(meta.minHeightM, static_cast<double>(t.minH));
      meta.maxHeightM = std::max(meta.maxHeightM, static_cast<double>(t.maxH));
    }
    if (withHeights.empty())
      return makeError(ErrorKind::InvalidInput, concat(o.dem, " gave no valid height at zoom ", maxZoom));
    meta.minZoom = std::min(o.minZoom.value_or(singleTileZoom(withHeights)), maxZoom);
    result = finishDataset(tmp, meta, progress, o.threads, o.jpegQuality, o.tasks);
    if (!result) return result.error();
    if (o.cancel && o.cancel->load())
      return makeError(ErrorKind::InvalidInput, "import interrupted; nothing was written");
    return {};
  });
  if (!written) return written.error();
  return result;
}

}  // namespace vegstream::datasets
