#pragma once
// Import of a DEM (+ imagery, possibly in another CRS, possibly as separate bands; + a NIR band)
// from any raster GDAL reads, by path or URL, into a dataset directory (dataset_format.h):
// `vegstream import --dem …`.
//
// Every output pixel centre of every XYZ tile (Web Mercator) is taken to longitude/latitude,
// into the source's CRS (geo/projection.h, PROJ), through the inverse of the source's affine to
// a source pixel position, and sampled (heights: bilinear or cubic, nodata if any neighbour is
// nodata; colour: bilinear renormalised over valid neighbours) from the window of the source
// that tile needs (raster_source.h), so memory is bounded by the tile and GDAL's block cache
// (--memory-mb), never by the raster's size. Tiles of the max zoom are produced in parallel;
// the lower zooms come from the pyramid builder. Everything is written into `.NAME.partial/`
// beside `out` (import_journal.h), renamed into place only when complete; --resume continues
// a killed import there.
//
// Zoom range. Max zoom, unless given: the first zoom whose ground resolution at the DEM's
// centre latitude is at least as fine as the DEM's pixel (7 % slack, so 30.4 m tiles count as
// 30 m), or — when the imagery is finer — as fine as the imagery's pixel, but at most 3 zooms
// beyond the DEM's; one max zoom serves both (heights are oversampled rather than colour
// thrown away, since plants are chosen from the colour). Min zoom, unless given: the highest
// zoom at which all tiles share one ancestor tile.

#include <atomic>
#include <filesystem>
#include <optional>
#include <string>

#include "core/log.h"
#include "core/result.h"
#include "core/task_runner.h"
#include "datasets/dataset_format.h"
#include "datasets/deshading.h"
#include "datasets/imagery_source.h"
#include "datasets/landcover_classes.h"
#include "datasets/ndvi_source.h"
#include "datasets/progress.h"
#include "geo/crs.h"

namespace vegstream::datasets {

// Heights outside this range are not on earth: they become nodata, with a warning that counts them.
inline constexpr double kMinPlausibleHeightM = -11000.0;
inline constexpr double kMaxPlausibleHeightM = 9000.0;
// Windows are read decimated beyond this many pixels on a side (4 tiles' worth: a source
// much finer than the max zoom).
inline constexpr int kMaxWindowSide = 1024;
// Highest zoom picked automatically (≈ 0.3 m pixels at the equator).
inline constexpr int kMaxAutoZoom = 19;

enum class HeightResampling { Bilinear, Cubic };

struct GeoTiffImportOptions {
  std::vector<std::string> dem;     // paths or URLs; several mosaic into one
  std::optional<geo::Crs> demCrs;   // --dem-crs: stated CRS (missing or corrupt), overrides the file
  std::optional<double> demNodata;  // --dem-nodata
  ImageryInput imagery;             // neither file nor bands: no imagery
  std::optional<NirInput> nir;      // --imagery-nir: an NDVI layer (needs imagery)
  // --landcover FILE: a class raster (ESA WorldCover, NLCD codes) stored as the landcover layer,
  // sampled by nearest class, never blended (landcover.h); its scheme stated
  // (--landcover-scheme) or detected from its codes; its CRS stated with --landcover-crs.
  struct Landcover {
    std::string file;
    std::optional<LandcoverScheme> scheme;
    std::optional<geo::Crs> crs;
  };
  std::optional<Landcover> landcover;
  // --canopy-height FILE: a canopy height model (metres above the ground; a declared foot unit is
  // converted) stored as the canopy layer at its own resolution (canopy_import.h); its CRS stated
  // with --canopy-height-crs.
  struct Canopy {
    std::string file;
    std::optional<geo::Crs> crs;
  };
  std::optional<Canopy> canopy;
  HeightResampling heightResampling = HeightResampling::Bilinear;
  // When the imagery was taken (--imagery-datetime, ISO 8601 with a zone; empty: unknown):
  // recorded in dataset.json, and the sun at the dataset's centre then de-shades the imagery.
  std::string imageryDatetime;
  // The acquisition sun as stated (--imagery-sun AZ,EL, e.g. a Landsat MTL's SUN_AZIMUTH and
  // SUN_ELEVATION): wins over the datetime's.
  std::optional<SunAngles> imagerySun;
  // De-shade reflectance and sRGB imagery (deshading.h) under the acquisition sun: from
  // imagerySun, else imageryDatetime, else estimated (sun_estimate.h). Off: --deshading off.
  bool deshade = true;
  double directFraction = kDirectFraction;

  std::filesystem::path out;
  std::string name;  // empty: the last component of `out`
  std::string attribution;
  ElevationEncoding encoding = ElevationEncoding::Terrarium;
  ImageryFormat imageryFormat = ImageryFormat::Jpeg;
  int jpegQuality = 90;
  std::optional<int> maxZoom;
  std::optional<int> minZoom;

  // Memory budget, MiB: a quarter goes to GDAL's block cache, the rest bounds the windows the
  // workers hold (each ≤ kMaxWindowSide² pixels) and the statistics' overview.
  size_t memoryMb = 512;
  bool resume = false;                        // continue the import killed at this --out
  uint64_t maxTiles = 1'000'000;              // tiles at the max zoom; more is refused (pick --max-zoom)
  int threads = 0;                            // 0: all cores
  TaskRunner* tasks = nullptr;                // runs the workers (outlives the call); null: a pool made for the call
  const std::atomic<bool>* cancel = nullptr;  // set (e.g. by SIGINT): stop, leave nothing
};

// Errors name the file and the problem: as RasterSource::open, a CRS PROJ cannot use, DEM and imagery that do not overlap, a DEM without one valid height, `out` that
// exists and is not empty or cannot be created, a NIR file without imagery or that prepareNdvi
// refuses (all InvalidInput / NotFound / Unsupported); a failed tile write is Io.
Result<DatasetMeta> importGeoTiff(const GeoTiffImportOptions& options, const Logger& log, ProgressSink& progress);

// The first zoom whose ground resolution at latDeg is at least as fine as metresPerPixel
// (7 % slack), clamped to 0 … kMaxAutoZoom.
int naturalZoom(double metresPerPixel, double latDeg);

// Checks that `out` can become a new dataset directory: it does not exist or is an empty
// directory, and its nearest existing ancestor is a writable directory. InvalidInput otherwise.
Status checkOutputDirectory(const std::filesystem::path& out);

}  // namespace vegstream::datasets
