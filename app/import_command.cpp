// `vegstream import` (import_command.h): parses the options into the importers' option structs,
// runs the GeoTIFF or the XYZ importer with a progress bar, and prints the summary line.

#include "app/import_command.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <csignal>
#include <cstdio>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/exit_codes.h"
#include "datasets/deshading_plan.h"
#include "datasets/geotiff_import.h"
#include "datasets/import_journal.h"
#include "datasets/progress.h"
#include "datasets/xyz_import.h"
#include "geo/crs.h"

namespace vegstream::app {
namespace {
namespace fs = std::filesystem;
using datasets::DatasetMeta;

// Set by SIGINT / SIGTERM; the importer polls it between tiles and then removes its temporary
// directory. A signal handler can only reach a static.
std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted = true; }

Error userError(const std::string& message) { return makeError(ErrorKind::InvalidInput, message); }

std::vector<fs::path> splitList(const std::string& text) {
  std::vector<fs::path> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.emplace_back(item);
  return out;
}

Result<geo::Crs> crsOption(const std::string& flag, const std::string& text) {
  auto crs = geo::Crs::fromUserInput(text);
  if (!crs) return makeError(crs.error().kind, flag + ": " + crs.error().message);
  return crs;
}

// "1,2,3" → {1, 2, 3}: positive band numbers.
Result<std::vector<int>> bandList(const std::string& text) {
  std::vector<int> out;
  for (const auto& item : splitList(text)) {
    char* end = nullptr;
    const long b = std::strtol(item.c_str(), &end, 10);
    if (end != item.c_str() + item.string().size() || b < 1 || b > 65535)
      return userError("--bands '" + text + "': expected band numbers from 1, e.g. 1,2,3");
    out.push_back(static_cast<int>(b));
  }
  if (out.size() != 3 && out.size() != 1) return userError("--bands '" + text + "': expected three bands R,G,B or one");
  return out;
}


// A finite number, the whole text: "--reflectance-scale 'nan': expected a finite number".
Result<double> numberOption(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
    std::string m = flag;
    m += " '";
    m += text;
    m += "': expected a finite number";
    return userError(m);
  }
  return v;
}

// --radiometry, --reflectance-scale/-offset, --imagery-datetime, --imagery-sun, --deshading.
Status radiometryOptions(const ImportOptions& o, datasets::GeoTiffImportOptions& g) {
  auto method = datasets::parseRadiometryMethod(o.radiometry);
  if (!method) return method.error();
  g.imagery.radiometry.method = *method;
  if (!o.reflectanceScale.empty()) {
    auto v = numberOption("--reflectance-scale", o.reflectanceScale);
    if (!v) return v.error();
    if (*v <= 0.0) return userError("--reflectance-scale '" + o.reflectanceScale + "': expected a number above 0");
    g.imagery.radiometry.scale = *v;
  }
  if (!o.reflectanceOffset.empty()) {
    auto v = numberOption("--reflectance-offset", o.reflectanceOffset);
    if (!v) return v.error();
    g.imagery.radiometry.offset = *v;
  }
  if (!o.imageryDatetime.empty()) {
    if (auto ms = datasets::imageryUnixMs(o.imageryDatetime); !ms) return ms.error();
    g.imageryDatetime = o.imageryDatetime;
  }
  if (!o.imagerySun.empty()) {
    const auto comma = o.imagerySun.find(',');
    auto az = numberOption("--imagery-sun", o.imagerySun.substr(0, comma));
    auto el = numberOption("--imagery-sun", comma == std::string::npos ? "" : o.imagerySun.substr(comma + 1));
    if (!az || !el || *az < 0.0 || *az >= 360.0 || *el < -90.0 || *el > 90.0)
      return userError("--imagery-sun '" + o.imagerySun +
                       "': expected AZIMUTH,ELEVATION in degrees (0 <= azimuth < 360 clockwise from north, "
                       "-90 … 90)");
    g.imagerySun = datasets::SunAngles{*az, *el};
  }
  if (o.deshading != "on" && o.deshading != "off")
    return userError("--deshading '" + o.deshading + "': expected on or off");
  g.deshade = o.deshading == "on";
  return {};
}

Result<datasets::ImageryFormat> imageryFormatOption(const std::string& text, datasets::ImageryFormat fallback) {
  if (text.empty()) return fallback;
  if (text == "jpeg" || text == "jpg") return datasets::ImageryFormat::Jpeg;
  if (text == "png") return datasets::ImageryFormat::Png;
  std::string m = "--imagery-format '";
  m += text;
  m += "': expected jpeg or png";
  return userError(m);
}

Result<datasets::GeoTiffImportOptions> geoTiffOptions(const ImportOptions& o) {
  datasets::GeoTiffImportOptions g;
  g.dem = o.dem;
  if (!o.demCrs.empty()) {
    auto e = crsOption("--dem-crs", o.demCrs);
    if (!e) return e.error();
    g.demCrs = *e;
  }
  if (o.demNodataOpt && o.demNodataOpt->count()) g.demNodata = o.demNodata;
  if (!o.imagery.empty() && !o.imageryBands.empty())
    return userError("--imagery and --imagery-bands exclude each other: give one RGB file or three band files");
  g.imagery.files = o.imagery;
  if (!o.bands.empty()) {
    if (o.imagery.empty()) return userError("--bands chooses bands of --imagery FILE, which was not given");
    auto b = bandList(o.bands);
    if (!b) return b.error();
    g.imagery.bandNumbers = *b;
  }
  if (!o.imageryBands.empty()) {
    for (const auto& f : splitList(o.imageryBands)) g.imagery.bands.push_back(f.string());
    if (g.imagery.bands.size() != 3) {
      std::string m = "--imagery-bands '";
      m += o.imageryBands;
      m += "': expected three files R,G,B separated by commas";
      return userError(m);
    }
  }
  if (!o.imageryCrs.empty()) {
    auto e = crsOption("--imagery-crs", o.imageryCrs);
    if (!e) return e.error();
    g.imagery.assumeCrs = *e;
  }
  if (!o.stretch.empty()) {
    auto s = datasets::parseStretch(o.stretch);
    if (!s) return s.error();
    g.imagery.stretch = *s;
  }
  if (auto r = radiometryOptions(o, g); !r) return r.error();
  if (!o.imageryNir.empty() || o.nirBand > 0) {
    datasets::NirInput nir;
    nir.file = o.imageryNir;
    nir.band = std::max(o.nirBand, 1);
    if (o.imageryNir.empty()) {  // --nir-band alone: a band of the imagery file itself
      if (o.imagery.size() != 1)
        return userError("--nir-band without --imagery-nir takes the band from --imagery FILE: give one file");
      nir.file = o.imagery[0];
    }
    if (!o.imageryNirCrs.empty()) {
      auto e = crsOption("--imagery-nir-crs", o.imageryNirCrs);
      if (!e) return e.error();
      nir.assumeCrs = *e;
    }
    g.nir = std::move(nir);
  } else if (!o.imageryNirCrs.empty()) {
    return userError("--imagery-nir-crs states the CRS of --imagery-nir FILE, which was not given");
  }
  if (!o.landcover.empty()) {
    datasets::GeoTiffImportOptions::Landcover l;
    l.file = o.landcover;
    auto scheme = datasets::parseLandcoverScheme(o.landcoverScheme);
    if (!scheme) return scheme.error();
    l.scheme = *scheme;
    if (!o.landcoverCrs.empty()) {
      auto e = crsOption("--landcover-crs", o.landcoverCrs);
      if (!e) return e.error();
      l.crs = *e;
    }
    g.landcover = std::move(l);
  } else if (!o.landcoverCrs.empty() || o.landcoverScheme != "auto") {
    return userError("--landcover-scheme and --landcover-crs describe --landcover FILE, which was not given");
  }
  if (!o.canopyHeight.empty()) {
    datasets::GeoTiffImportOptions::Canopy c;
    c.file = o.canopyHeight;
    if (!o.canopyHeightCrs.empty()) {
      auto e = crsOption("--canopy-height-crs", o.canopyHeightCrs);
      if (!e) return e.error();
      c.crs = *e;
    }
    g.canopy = std::move(c);
  } else if (!o.canopyHeightCrs.empty()) {
    return userError("--canopy-height-crs states the CRS of --canopy-height FILE, which was not given");
  }
  auto enc = datasets::parseElevationEncoding(o.encoding);
  if (!enc) return enc.error();
  g.encoding = *enc;
  auto fmt = imageryFormatOption(o.imageryFormat, datasets::ImageryFormat::Jpeg);
  if (!fmt) return fmt.error();
  g.imageryFormat = *fmt;
  g.out = o.out;
  g.name = o.name;
  g.attribution = o.attribution;
  g.jpegQuality = o.jpegQuality;
  if (o.maxZoom >= 0) g.maxZoom = o.maxZoom;
  if (o.minZoom >= 0) g.minZoom = o.minZoom;
  if (g.minZoom && g.maxZoom && *g.minZoom > *g.maxZoom) return userError("--min-zoom is greater than --max-zoom");
  if (o.heightResampling == "cubic")
    g.heightResampling = datasets::HeightResampling::Cubic;
  else if (o.heightResampling != "bilinear") {
    std::string m = "--height-resampling '";
    m += o.heightResampling;
    m += "': expected bilinear or cubic";
    return userError(m);
  }
  if (o.memoryMb < 64) return userError("--memory-mb " + std::to_string(o.memoryMb) + ": expected at least 64");
  g.memoryMb = o.memoryMb;
  g.resume = o.resume;
  g.threads = o.threads;
  g.cancel = &gInterrupted;
  return g;
}

// --bounds W,S,E,N (degrees; W > E crosses the antimeridian).
Result<geo::GeoBounds> boundsOption(const std::string& text) {
  const std::vector<fs::path> parts = splitList(text);
  double v[4] = {};
  bool good = parts.size() == 4 && std::count(text.begin(), text.end(), ',') == 3;
  for (size_t i = 0; good && i < 4; ++i) {
    auto n = numberOption("--bounds", parts[i].string());
    good = n.ok();
    if (good) v[i] = *n;
  }
  if (!good) return userError("--bounds '" + text + "': expected W,S,E,N in degrees (e.g. -112.5,36.0,-112.3,36.2)");
  const bool lonOk = v[0] >= -180.0 && v[0] <= 180.0 && v[2] >= -180.0 && v[2] <= 180.0 && v[0] != v[2];
  if (!lonOk || v[1] >= v[3] || v[1] < -90.0 || v[3] > 90.0)
    return userError("--bounds '" + text + "': expected -180 <= W, E <= 180, W != E and -90 <= S < N <= 90");
  return geo::GeoBounds{v[0], v[1], v[2], v[3]};
}

Result<DatasetMeta> runXyz(const ImportOptions& o, const Logger& log, datasets::ProgressSink& progress) {
  datasets::XyzImportOptions x;
  x.elevationTemplate = o.xyzElevation;
  if (!o.xyzImagery.empty()) x.imageryTemplate = o.xyzImagery;
  auto enc = datasets::parseElevationEncoding(o.encoding);
  if (!enc) return enc.error();
  if (!o.encodingOpt || !o.encodingOpt->count())
    return userError("--xyz-elevation needs --encoding terrain-rgb or --encoding terrarium (the tiles' encoding)");
  x.encoding = *enc;
  x.out = o.out;
  x.name = o.name;
  x.attribution = o.attribution;
  auto fmt = imageryFormatOption(o.imageryFormat, datasets::ImageryFormat::Png);
  if (!fmt) return fmt.error();
  x.imageryFormat = *fmt;
  x.jpegQuality = o.jpegQuality;
  if (o.minZoom >= 0) x.minZoom = o.minZoom;
  if (o.maxZoom >= 0) x.maxZoom = o.maxZoom;
  if (!o.bounds.empty()) {
    auto b = boundsOption(o.bounds);
    if (!b) return b.error();
    x.bounds = *b;
  }
  x.threads = o.threads;
  x.http.allowRedirects = o.allowRedirects;
  x.cancel = &gInterrupted;
  return datasets::importXyzTiles(x, log, progress);
}

}  // namespace

CLI::App* addImportCommand(CLI::App& cli, ImportOptions& o) {
  auto* cmd = cli.add_subcommand("import", "DEM (+ imagery) from any raster GDAL reads, or XYZ tiles → a dataset");
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
    auto g = geoTiffOptions(o);
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
