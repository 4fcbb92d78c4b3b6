// `vegstream import --dem …` (geotiff_import.h): open and check the sources through GDAL, pick
// the zooms, produce the max zoom's tiles in parallel from source windows (tile_producer.h),
// then the shared finish (pyramid, dataset.json), all inside the partial directory
// (import_journal.h) renamed into place at the end.

#include "datasets/geotiff_import.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gdal.h>
#include <nlohmann/json.hpp>

#include "core/parallel_for.h"
#include "datasets/dataset_finish.h"
#include "datasets/canopy_import.h"
#include "datasets/deshading_plan.h"
#include "datasets/import_journal.h"
#include "datasets/landcover_layer.h"
#include "datasets/message.h"
#include "datasets/tile_producer.h"
#include "geo/gdal_quiet.h"
#include "geo/projection.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

std::string describe(const SourceGrid& g) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "%.2f m pixels", g.pixelSizeM());
  return concat(g.source().description(), ", ", buf);
}

SourceInfo sourceInfo(const std::string& role, const std::string& path, const SourceGrid& g, const std::string& more) {
  SourceInfo s{role, path, g.crs().name(), more.empty() ? describe(g) : concat(describe(g), ", ", more)};
  s.crsCode = g.crs().code();
  if (s.crsCode.empty()) s.crsProjjson = g.crs().projjson();
  s.resolutionM = std::round(g.pixelSizeM() * 1000.0) / 1000.0;
  s.driver = g.source().driver();
  return s;
}

std::string joined(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& x : v) out += (out.empty() ? "" : ",") + x;
  return out;
}

// What makes two imports the same import (--resume continues only that one): the inputs (with
// each local file's size and time) and every option that changes a tile.
std::string fingerprint(const GeoTiffImportOptions& o) {
  nlohmann::json j;
  const auto files = [](const std::vector<std::string>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& f : v) {
      std::error_code ec;
      const auto size = fs::file_size(f, ec);
      const auto time = fs::last_write_time(f, ec).time_since_epoch().count();
      a.push_back({f, ec ? 0 : size, ec ? 0 : time});
    }
    return a;
  };
  j["dem"] = files(o.dem);
  j["imagery"] = files(o.imagery.files);
  j["bands"] = files(o.imagery.bands);
  j["band_numbers"] = o.imagery.bandNumbers;
  if (o.nir) j["nir"] = {files({o.nir->file}), o.nir->band};
  if (o.landcover)
    j["landcover"] = {files({o.landcover->file}), o.landcover->scheme ? toString(*o.landcover->scheme) : "auto",
                      o.landcover->crs ? o.landcover->crs->wkt() : ""};
  if (o.canopy) j["canopy"] = {files({o.canopy->file}), o.canopy->crs ? o.canopy->crs->wkt() : ""};
  j["crs"] = {o.demCrs ? o.demCrs->wkt() : "", o.imagery.assumeCrs ? o.imagery.assumeCrs->wkt() : ""};
  j["options"] = {o.demNodata.value_or(NAN), static_cast<int>(o.heightResampling), o.imageryDatetime,
                  o.imagerySun ? o.imagerySun->azimuthDeg : NAN, o.imagerySun ? o.imagerySun->elevationDeg : NAN,
                  o.deshade, o.directFraction, static_cast<int>(o.encoding), static_cast<int>(o.imageryFormat),
                  o.jpegQuality, o.maxZoom.value_or(-1), o.minZoom.value_or(-1),
                  static_cast<int>(o.imagery.radiometry.method), o.imagery.radiometry.scale.value_or(NAN),
                  o.imagery.radiometry.offset.value_or(NAN), o.imagery.stretch ? o.imagery.stretch->lo : NAN,
                  o.imagery.stretch ? o.imagery.stretch->hi : NAN};
  return j.dump();
}

Status checkInputs(const GeoTiffImportOptions& o) {
  if (auto s = checkOutputDirectory(o.out); !s) return s;
  const bool withImagery = o.imagery.given();
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
  return {};
}

// The DEM's heights over its overview: a warning for the implausible ones, an error when none
// is valid.
Status checkHeights(const RasterSource& dem, uint64_t maxPixels, const Logger& log) {
  auto overview = dem.readOverview(maxPixels);
  if (!overview) return overview.error();
  uint64_t implausible = 0, valid = 0;
  for (const float v : overview->samples) {
    if (std::isnan(v)) continue;
    const bool ok = v >= kMinPlausibleHeightM && v <= kMaxPlausibleHeightM;
    implausible += !ok;
    valid += ok;
  }
  if (implausible)
    log->warn("{}: {} heights{} outside {} … {} m treated as nodata", dem.label(), implausible,
              overview->step.x > 1.0 ? " (of its overview)" : "", kMinPlausibleHeightM, kMaxPlausibleHeightM);
  if (valid == 0) return makeError(ErrorKind::InvalidInput, concat(dem.label(), " has no valid height (all nodata)"));
  return {};
}

struct Grids {
  const SourceGrid& dem;
  const PreparedImagery* imagery;
  const SourceGrid* imageryGrid;
  const NdviSource* ndvi;
  const SourceGrid* landcover;
  std::optional<LandcoverScheme> scheme;
  const CanopyLayer* canopy = nullptr;
};

int chooseMaxZoom(const GeoTiffImportOptions& o, const Grids& g, double lat) {
  int maxZoom = naturalZoom(g.dem.pixelSizeM(), lat);
  if (g.imageryGrid)
    maxZoom = std::max(maxZoom, std::min(naturalZoom(g.imageryGrid->pixelSizeM(), lat), maxZoom + 3));
  return o.maxZoom.value_or(maxZoom);
}

DatasetMeta initialMeta(const GeoTiffImportOptions& o, const Grids& g, int maxZoom) {
  DatasetMeta meta;
  meta.name = o.name.empty() ? defaultDatasetName(o.out) : o.name;
  meta.bounds = g.dem.extent();
  meta.maxZoom = maxZoom;
  meta.elevationEncoding = o.encoding;
  meta.attribution = o.attribution;
  meta.sources.push_back(sourceInfo("elevation", joined(o.dem), g.dem, ""));
  if (g.imageryGrid) {
    meta.imagery = o.imageryFormat;
    meta.imageryDatetime = o.imageryDatetime;
    meta.radiometry = g.imagery->radiometry;
    meta.colourCalibration = g.imagery->colourCalibration;
    const std::string paths = o.imagery.files.empty() ? joined(o.imagery.bands) : joined(o.imagery.files);
    meta.sources.push_back(sourceInfo("imagery", paths, *g.imageryGrid, g.imagery->description));
  }
  if (g.landcover) {
    meta.landcover = g.scheme;
    meta.sources.push_back(sourceInfo("landcover", o.landcover->file, *g.landcover,
                                      concat("classes of ", toString(*g.scheme), ", nearest class")));
  }
  if (g.canopy)
    meta.sources.push_back(sourceInfo("canopy", g.canopy->file, *g.canopy->grid, "canopy heights (m), bilinear"));
  if (g.ndvi) {
    meta.ndvi = true;
    SourceInfo nir{"nir", o.nir->file, g.ndvi->nirCrs().name(), g.ndvi->description()};
    nir.crsCode = g.ndvi->nirCrs().code();
    meta.sources.push_back(nir);
  }
  return meta;
}

// Adds the max zoom's tiles to meta; an error when none has a height.
Status countTiles(const GeoTiffImportOptions& o, const std::vector<geo::TileId>& tiles,
                  const std::vector<TileRecord>& records, DatasetMeta& meta) {
  std::vector<geo::TileId> withHeights;
  meta.minHeightM = std::numeric_limits<double>::infinity();
  meta.maxHeightM = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < tiles.size(); ++i) {
    const TileRecord& t = records[i];
    meta.bytes += t.bytes;
    meta.imageryTiles += t.imagery;
    meta.ndviTiles += t.ndvi;
    meta.landcoverTiles += t.landcover;
    if (!t.elevation) continue;
    ++meta.elevationTiles;
    withHeights.push_back(tiles[i]);
    meta.minHeightM = std::min(meta.minHeightM, static_cast<double>(t.minH));
    meta.maxHeightM = std::max(meta.maxHeightM, static_cast<double>(t.maxH));
  }
  if (withHeights.empty())
    return makeError(ErrorKind::InvalidInput, concat(joined(o.dem), " gave no valid height at zoom ", meta.maxZoom));
  if (meta.ndvi && meta.ndviTiles == 0)
    return makeError(ErrorKind::InvalidInput,
                     concat("the near-infrared file ", o.nir->file,
                            " gives no NDVI over the imagery: no pixel where both have data (or NIR + red > 0)"));
  meta.minZoom = std::min(o.minZoom.value_or(singleTileZoom(withHeights)), meta.maxZoom);
  return {};
}

Result<std::optional<ImageryTiling>> planImagery(const GeoTiffImportOptions& o, const Grids& g,
                                                 const std::vector<geo::TileId>& tiles, RadiometryRecord& record,
                                                 const Logger& log) {
  if (!g.imagery) return std::optional<ImageryTiling>();
  TileSources src{&g.dem, g.imagery, g.imageryGrid, nullptr, nullptr, nullptr, o.heightResampling};
  ImageryTiling tiling{g.imagery->linear, std::nullopt, o.directFraction};
  auto plan = planDeshading(
      o, record, tiling, tiles, g.dem.extent().centre(),
      [&](const geo::TileId& id) {
        auto h = tileHeights(src, id);
        return h ? *h : std::vector<float>(static_cast<size_t>(kTileSize * kTileSize), NAN);
      },
      [&](const geo::TileId& id) {
        auto t = tileImagery(src, id);
        return t ? std::move(*t) : std::optional<TileImagery>();
      },
      log);
  if (!plan) return plan.error();
  tiling.sun = plan->sun;
  record.deshading = plan->record;
  return std::optional<ImageryTiling>(tiling);
}

Result<DatasetMeta> importTiles(const GeoTiffImportOptions& o, const Grids& g, const Logger& log,
                                ProgressSink& progress) {
  const double lat = g.dem.extent().centre().y;
  const int maxZoom = chooseMaxZoom(o, g, lat);
  uint64_t tileCount = 0;
  for (const auto& r : geo::tileRangesCovering(g.dem.extent(), maxZoom)) tileCount += static_cast<uint64_t>(r.count());
  if (tileCount > o.maxTiles)
    return makeError(ErrorKind::InvalidInput,
                     concat(joined(o.dem), " at zoom ", maxZoom, " needs ", tileCount, " tiles, more than the limit of ",
                            o.maxTiles, "; choose a lower --max-zoom"));
  const std::vector<geo::TileId> tiles = geo::tilesCovering(g.dem.extent(), maxZoom);
  log->info("{}: {} ({:.2f} m pixels, {}) → zoom {} ({:.1f} m pixels), {} tiles", g.dem.source().label(),
            g.dem.crs().name(), g.dem.pixelSizeM(), g.dem.source().driver(), maxZoom,
            geo::groundResolution(lat, maxZoom, kTileSize), tiles.size());
  if (g.imageryGrid)
    log->info("{}: {} ({:.2f} m pixels), {}", g.imageryGrid->source().label(), g.imageryGrid->crs().name(),
              g.imageryGrid->pixelSizeM(), g.imagery->radiometryChoice);
  DatasetMeta meta = initialMeta(o, g, maxZoom);
  RadiometryRecord none;
  auto tiling = planImagery(o, g, tiles, meta.radiometry ? *meta.radiometry : none, log);
  if (!tiling) return tiling.error();

  auto journal = ImportJournal::open(o.out, fingerprint(o), o.resume);
  if (!journal) return journal.error();
  if (journal->doneCount()) log->info("--resume: {} of {} tiles already done", journal->doneCount(), tiles.size());
  const auto fail = [&](Error e) -> Result<DatasetMeta> {
    journal->discard();
    return e;
  };
  progress.addTotal(tiles.size());
  progress.stage(concat("zoom ", maxZoom));
  std::vector<TileRecord> records(tiles.size());
  const TileSources src{&g.dem, g.imagery,   g.imageryGrid,    *tiling ? &**tiling : nullptr,
                        g.ndvi, g.landcover, o.heightResampling};
  Status s = parallelFor(tiles.size(), o.threads, o.tasks, [&](size_t i) -> Status {
    if (o.cancel && o.cancel->load()) return makeError(ErrorKind::InvalidInput, "import interrupted; nothing was written");
    if (const TileRecord* done = journal->done(tiles[i])) {
      records[i] = *done;
    } else {
      if (auto t = produceTile(journal->dir(), tiles[i], src, o, records[i]); !t) return t;
      if (auto t = journal->record(tiles[i], records[i]); !t) return t;
    }
    progress.tileDone(records[i].bytes);
    return {};
  });
  if (!s) return fail(s.error());
  if (auto c = countTiles(o, tiles, records, meta); !c) return fail(c.error());
  if (g.canopy)
    if (auto c = importCanopyTiles(journal->dir(), *g.canopy, g.dem.extent(), o.maxTiles, o.threads, o.tasks, progress,
                                   meta);
        !c)
      return fail(c.error());
  auto result = finishDataset(journal->dir(), meta, progress, o.threads, o.jpegQuality, o.tasks);
  if (!result) return fail(result.error());
  if (o.cancel && o.cancel->load()) return fail(makeError(ErrorKind::InvalidInput, "import interrupted; nothing was written"));
  if (auto done = journal->complete(o.out); !done) return fail(done.error());
  return result;
}

// The imagery of a --dem import, its grid, and the NDVI source over that grid.
struct ImageryInputs {
  std::optional<PreparedImagery> imagery;
  std::optional<SourceGrid> grid;
  std::optional<NdviSource> ndvi;
};

// Opens the imagery (and the near-infrared raster when given) into out; an error when it does
// not overlap the DEM.
Status openImagery(const GeoTiffImportOptions& o, const std::string& demLabel, const SourceGrid& demGrid,
                   const Logger& log, ImageryInputs& out) {
  auto prepared = PreparedImagery::open(o.imagery, log);
  if (!prepared) return prepared.error();
  out.imagery = std::move(*prepared);
  auto grid = SourceGrid::make(out.imagery->source());
  if (!grid) return grid.error();
  out.grid = std::move(*grid);
  if (!extentsOverlap(demGrid.extent(), out.grid->extent()))
    return makeError(ErrorKind::InvalidInput,
                     concat("the DEM ", demLabel, " (", extentText(demGrid.extent()), ") and the imagery ",
                            o.imagery.label(), " (", extentText(out.grid->extent()), ") do not overlap"));
  if (o.nir) {
    auto n = NdviSource::open(*o.nir, *out.grid, log);
    if (!n) return n.error();
    out.ndvi = std::move(*n);
  }
  return {};
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
  if (auto s = checkInputs(o); !s) return s.error();
  geo::ensureGdal();
  GDALSetCacheMax64(static_cast<GIntBig>(std::max<size_t>(o.memoryMb / 4, 16)) << 20);
  const uint64_t overviewPixels = std::clamp<uint64_t>(o.memoryMb * 1024 * 1024 / 40, 1'000'000, kStatisticsPixels);

  SourceOptions demOptions;
  demOptions.assumeCrs = o.demCrs;
  demOptions.nodataOverride = o.demNodata;
  demOptions.heights = true;
  auto dem = RasterSource::open(o.dem, demOptions);
  if (!dem) return dem.error();
  if (dem->channels() != 1)
    return makeError(ErrorKind::InvalidInput, concat(dem->label(), " has ", dem->channels(),
                                                     " bands; a DEM has one (heights): choose it with --dem-band"));
  if (auto s = checkHeights(*dem, overviewPixels, log); !s) return s.error();
  auto demGrid = SourceGrid::make(*dem);
  if (!demGrid) return demGrid.error();

  ImageryInputs in;  // stays where it is: its grid points into its imagery's source
  if (o.imagery.given())
    if (Status st = openImagery(o, dem->label(), *demGrid, log, in); !st) return st.error();
  const std::optional<PreparedImagery>& imagery = in.imagery;
  GeoTiffImportOptions options = o;
  if (options.imageryDatetime.empty() && imagery)
    if (auto t = imagery->source().acquisitionDatetime()) {
      log->info("{}: taken at {} (its metadata)", o.imagery.label(), *t);
      options.imageryDatetime = *t;
    }
  std::optional<LandcoverLayer> landcover;
  if (o.landcover) {
    auto l = openLandcover(*o.landcover, *demGrid, overviewPixels, log);
    if (!l) return l.error();
    landcover = std::move(*l);
  }
  std::optional<CanopyLayer> canopy;
  if (o.canopy) {
    auto c = openCanopy(o.canopy->file, o.canopy->crs, *demGrid, overviewPixels, log);
    if (!c) return c.error();
    canopy = std::move(*c);
  }
  const Grids grids{*demGrid,
                    imagery ? &*imagery : nullptr,
                    in.grid ? &*in.grid : nullptr,
                    in.ndvi ? &*in.ndvi : nullptr,
                    landcover ? landcover->grid.get() : nullptr,
                    landcover ? std::optional<LandcoverScheme>(landcover->scheme) : std::nullopt,
                    canopy ? &*canopy : nullptr};
  return importTiles(options, grids, log, progress);
}

}  // namespace vegstream::datasets
