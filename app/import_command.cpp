// `vegstream import` (import_command.h): registers the options, runs the GeoTIFF or the XYZ
// importer (their option structs from import_options.h) with a progress bar, and prints the
// summary line.

#include "app/import_command.h"

#include <atomic>
#include <csignal>
#include <cstdio>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "app/import_options.h"
#include "datasets/import_journal.h"
#include "datasets/progress.h"

namespace vegstream::app {
namespace {
using datasets::DatasetMeta;

// Set by SIGINT / SIGTERM; the importer polls it between tiles and then removes its temporary
// directory. A signal handler can only reach a static.
std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted = true; }

Error userError(const std::string& message) { return makeError(ErrorKind::InvalidInput, message); }

Result<DatasetMeta> runXyz(const ImportOptions& o, const Logger& log, datasets::ProgressSink& progress) {
  auto x = xyzImportOptions(o, &gInterrupted);
  if (!x) return x.error();
  return datasets::importXyzTiles(*x, log, progress);
}

// --dem, the imagery and its bands, and the NIR, landcover and canopy rasters (with their CRSs).
void addRasterInputs(CLI::App* cmd, ImportOptions& o) {
  cmd->add_option("--dem", o.dem,
                  "DEM: any raster GDAL reads (GeoTIFF, COG, VRT, JP2, HGT, IMG, …), a path or an http(s) URL (read "
                  "by range requests); several files mosaic into one. Heights in metres, or feet when the file says so");
  cmd->add_option("--imagery", o.imagery,
                  "Imagery: RGB, grey or multi-band (choose with --bands), any CRS PROJ knows, path or URL; several "
                  "mosaic");
  cmd->add_option("--bands", o.bands, "Bands of --imagery as R,G,B (e.g. 1,2,3; default: the bands that are not alpha)");
  cmd->add_option("--imagery-bands", o.imageryBands, "Imagery as three single-band files R.tif,G.tif,B.tif");
  cmd->add_option("--imagery-nir", o.imageryNir,
                  "Near-infrared raster (any CRS) → an NDVI layer with the imagery's red; --nir-band picks its band");
  cmd->add_option("--nir-band", o.nirBand,
                  "The near-infrared band (of --imagery-nir, or of --imagery itself when alone, e.g. NAIP's 4)")
      ->check(CLI::Range(1, 65535));
  cmd->add_option("--landcover", o.landcover,
                  "A landcover class raster (ESA WorldCover or NLCD codes; any format and CRS) → the landcover "
                  "layer, resampled by nearest class, never blended; query reports the class");
  cmd->add_option("--landcover-scheme", o.landcoverScheme,
                  "The landcover codes: worldcover, nlcd, or auto (detected from the codes present)")
      ->capture_default_str();
  cmd->add_option("--landcover-crs", o.landcoverCrs, "The landcover raster's CRS when it has none or a wrong one");
  cmd->add_option("--canopy-height", o.canopyHeight,
                  "A canopy height model (heights of vegetation above the ground, metres or a declared foot unit; "
                  "any format and CRS) → the canopy layer at its own resolution; trees stand at its crowns");
  cmd->add_option("--canopy-height-crs", o.canopyHeightCrs,
                  "The canopy height model's CRS when it has none or a wrong one");
  cmd->add_option("--imagery-nir-crs", o.imageryNirCrs,
                  "The NIR file's CRS (EPSG:N, WKT or PROJJSON) when it has none or a wrong one");
}

// What the imagery's numbers are and its de-shading; the height resampling, the DEM's nodata
// and the CRSs of the DEM and the imagery.
void addRadiometryOptions(CLI::App* cmd, ImportOptions& o) {
  cmd->add_option("--stretch", o.stretch,
                  "Display stretch to 0…255 (with --radiometry stretch or auto): percentiles p1,p99 or values LO,HI");
  cmd->add_option("--radiometry", o.radiometry,
                  "What the imagery's numbers are: reflectance (DN x scale + offset, dark-object subtracted, "
                  "stored as sRGB-encoded albedo), srgb (8-bit photographs, as stored), stretch (display colours, "
                  "not albedo), or auto: 8-bit -> srgb; Landsat digital numbers (a product or scene id such as "
                  "LC08_L1TP_... or LC80380342015230LGN00, or 'landsat', in the file names, and values that scale "
                  "to reflectances) -> reflectance; other data beyond 8 bits -> stretch")
      ->capture_default_str();
  cmd->add_option("--reflectance-scale", o.reflectanceScale,
                  "Reflectance per digital number (default 2e-5, Landsat 8/9 Level-1; 2.75e-5 when the names say "
                  "Level-2)");
  cmd->add_option("--reflectance-offset", o.reflectanceOffset,
                  "Reflectance at digital number 0 (default -0.1, Landsat 8/9 Level-1; -0.2 for Level-2)");
  cmd->add_option("--imagery-datetime", o.imageryDatetime,
                  "When the imagery was taken, ISO 8601 with a zone (2015-08-18T17:58:00Z): recorded, and its sun "
                  "de-shades the imagery");
  cmd->add_option("--imagery-sun", o.imagerySun,
                  "The acquisition sun as AZIMUTH,ELEVATION degrees (a Landsat MTL's SUN_AZIMUTH, SUN_ELEVATION); "
                  "wins over --imagery-datetime's");
  cmd->add_option("--deshading", o.deshading,
                  "on: take the acquisition shading out of reflectance and srgb imagery with the DEM's normals and "
                  "the sun (stated, from --imagery-datetime, or estimated from the imagery); off: keep it")
      ->capture_default_str();
  cmd->add_option("--height-resampling", o.heightResampling,
                  "bilinear, or cubic (Catmull-Rom: keeps the DEM's values at its pixel centres without kinks)")
      ->capture_default_str();
  o.demNodataOpt = cmd->add_option("--dem-nodata", o.demNodata, "DEM nodata value (overrides the file's)");
  cmd->add_option("--dem-crs", o.demCrs, "The DEM's CRS (EPSG:N, WKT or PROJJSON) when it has none or a wrong one");
  cmd->add_option("--imagery-crs", o.imageryCrs,
                  "The imagery's CRS (EPSG:N, WKT or PROJJSON) when it has none or a wrong one");
}

// The XYZ form: --xyz-elevation, --xyz-imagery, --allow-redirects, --bounds.
void addXyzOptions(CLI::App* cmd, ImportOptions& o) {
  cmd->add_option("--xyz-elevation", o.xyzElevation,
                  "Elevation tiles (instead of --dem): a template 'DIR/{z}/{x}/{y}.png' or 'https://host/{z}/{x}/{y}.png' "
                  "({-y}: TMS rows), an .mbtiles file, or a .pmtiles file or URL; 256- or 512-pixel tiles (512 are "
                  "split into the 256 of the next zoom)");
  cmd->add_option("--xyz-imagery", o.xyzImagery,
                  "Imagery tiles (with --xyz-elevation), in any of --xyz-elevation's forms");
  cmd->add_flag("--allow-redirects", o.allowRedirects,
                "URL templates and PMTiles URLs: follow HTTP redirects to other hosts too (without it, only to "
                "the URL's own host; never to anything but http:// or https://)");
  cmd->add_option("--bounds", o.bounds,
                  "W,S,E,N degrees: the area of an XYZ import; required for URL templates, else overrides an "
                  "archive's bounds");
}

// Both forms: the encoding, the output, the zooms, the memory budget, --resume and --threads.
void addOutputOptions(CLI::App* cmd, ImportOptions& o) {
  o.encodingOpt = cmd->add_option("--encoding", o.encoding,
                                  "terrarium or terrain-rgb: the output's (--dem) or the tiles' (--xyz-elevation)")
                      ->capture_default_str();
  cmd->add_option("--imagery-format", o.imageryFormat, "jpeg or png (default: jpeg for --dem, png for XYZ)");
  cmd->add_option("--out", o.out, "Dataset directory to create (must not exist or be empty)")->required();
  cmd->add_option("--name", o.name, "Dataset name (default: the --out directory's name)");
  cmd->add_option("--attribution", o.attribution, "Source attribution, stored in dataset.json");
  cmd->add_option("--max-zoom", o.maxZoom,
                  "Finest zoom (default: from the source resolution); with --xyz-elevation the source's zoom to "
                  "read (default: its finest; required for URL templates)")
      ->check(CLI::Range(0, 22));
  cmd->add_option("--min-zoom", o.minZoom, "Coarsest zoom (default: the data in one tile)")->check(CLI::Range(0, 22));
  cmd->add_option("--jpeg-quality", o.jpegQuality, "JPEG quality of imagery tiles")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  cmd->add_option("--memory-mb", o.memoryMb,
                  "Memory budget in MiB: a quarter for GDAL's block cache, the rest for the windows being resampled "
                  "and the imagery statistics; the source's size does not matter")
      ->capture_default_str();
  cmd->add_flag("--resume", o.resume,
                "Continue the import that was killed at this --out (same inputs and options), from its .NAME.partial "
                "directory");
  cmd->add_option("--threads", o.threads, "Worker threads (0: all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
}

}  // namespace

CLI::App* addImportCommand(CLI::App& cli, ImportOptions& o) {
  auto* cmd = cli.add_subcommand("import", "DEM (+ imagery) from any raster GDAL reads, or XYZ tiles → a dataset");
  // In this order: the order --help lists them.
  addRasterInputs(cmd, o);
  addRadiometryOptions(cmd, o);
  addXyzOptions(cmd, o);
  addOutputOptions(cmd, o);
  return cmd;
}

int runImport(const ImportOptions& o, const Logger& log) {
  if (o.dem.empty() == o.xyzElevation.empty())
    return reportError(log,
                       userError("import needs exactly one of --dem FILE or --xyz-elevation 'DIR/{z}/{x}/{y}.png'"));
  auto lock = datasets::lockImportOutput(o.out);
  if (!lock) return reportError(log, lock.error());
  gInterrupted = false;
  auto previousInt = std::signal(SIGINT, onInterrupt);
  auto previousTerm = std::signal(SIGTERM, onInterrupt);
  datasets::ProgressReporter progress("import");
  Result<DatasetMeta> meta = makeError(ErrorKind::Internal, "no import ran");
  if (!o.dem.empty() && !o.bounds.empty()) {
    meta = userError("--bounds is the area of an XYZ import; a --dem import covers its rasters' extent");
  } else if (!o.dem.empty()) {
    auto g = geoTiffImportOptions(o, &gInterrupted);
    meta = g ? datasets::importGeoTiff(*g, log, progress) : Result<DatasetMeta>(g.error());
  } else {
    if (!o.imagery.empty() || !o.imageryBands.empty() || !o.stretch.empty() || !o.imageryNir.empty() ||
        !o.bands.empty() || o.nirBand > 0 || !o.landcover.empty() || !o.canopyHeight.empty() ||
        !o.imageryDatetime.empty() || !o.imagerySun.empty() || o.radiometry != "auto")
      meta = userError(
          "--imagery, --imagery-bands, --imagery-nir, --stretch, --radiometry, --imagery-datetime, --canopy-height and "
          "--imagery-sun go with --dem; use --xyz-imagery with --xyz-elevation");
    else
      meta = runXyz(o, log, progress);
  }
  progress.finish();
  std::signal(SIGINT, previousInt);
  std::signal(SIGTERM, previousTerm);
  if (gInterrupted) {
    log->error("import interrupted: nothing was written to {}", o.out);
    return 130;
  }
  if (!meta) return reportError(log, meta.error());
  const uint64_t tiles = meta->elevationTiles + meta->imageryTiles + meta->ndviTiles + meta->landcoverTiles;
  const double s = progress.seconds();
  std::string ndvi = meta->ndvi ? ", " + std::to_string(meta->ndviTiles) + " NDVI" : std::string();
  if (meta->landcover) ndvi += ", " + std::to_string(meta->landcoverTiles) + " landcover";
  if (meta->canopyZoom) ndvi += ", " + std::to_string(meta->canopyTiles) + " canopy (zoom " + std::to_string(*meta->canopyZoom) + ")";
  log->info(
      "imported {}: {} tiles ({} elevation, {} imagery{}), zooms {}…{}, heights {:.1f}…{:.1f} m, {:.1f} MB, "
      "{:.2f} s ({:.0f} tiles/s) → {}",
      meta->name, tiles, meta->elevationTiles, meta->imageryTiles, ndvi, meta->minZoom, meta->maxZoom, meta->minHeightM,
      meta->maxHeightM, static_cast<double>(meta->bytes) / 1048576.0, s, s > 0 ? static_cast<double>(tiles) / s : 0.0,
      o.out);
  return kExitOk;
}

}  // namespace vegstream::app
