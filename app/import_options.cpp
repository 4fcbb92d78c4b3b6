// `vegstream import`'s options (import_options.h) → the importers' option structs: every text
// option checked, and the first problem returned as a user error naming the option.
#include "app/import_options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "datasets/deshading_plan.h"
#include "geo/crs.h"

namespace vegstream::app {
namespace {
namespace fs = std::filesystem;

Error userError(const std::string& message) { return makeError(ErrorKind::InvalidInput, message); }

std::vector<fs::path> splitList(const std::string& text) {
  std::vector<fs::path> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.emplace_back(item);
  return out;
}

// A CRS option: `out` := the CRS `text` names, when it names one (empty: not given, `out` left as
// it is); an error naming `flag` when it does not parse.
Status crsOption(const std::string& flag, const std::string& text, std::optional<geo::Crs>& out) {
  if (text.empty()) return {};
  auto crs = geo::Crs::fromUserInput(text);
  if (!crs) return makeError(crs.error().kind, flag + ": " + crs.error().message);
  out = std::move(*crs);
  return {};
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

// --dem, --dem-crs, --dem-nodata.
Status demOptions(const ImportOptions& o, datasets::GeoTiffImportOptions& g) {
  g.dem = o.dem;
  if (Status s = crsOption("--dem-crs", o.demCrs, g.demCrs); !s) return s;
  if (o.demNodataOpt && o.demNodataOpt->count()) g.demNodata = o.demNodata;
  return {};
}

// --imagery or --imagery-bands, --bands, --imagery-crs, --stretch.
Status imageryOptions(const ImportOptions& o, datasets::GeoTiffImportOptions& g) {
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
  if (Status s = crsOption("--imagery-crs", o.imageryCrs, g.imagery.assumeCrs); !s) return s;
  if (!o.stretch.empty()) {
    auto s = datasets::parseStretch(o.stretch);
    if (!s) return s.error();
    g.imagery.stretch = *s;
  }
  return {};
}

// --imagery-nir or --nir-band, --imagery-nir-crs: the NDVI layer.
Status nirOptions(const ImportOptions& o, datasets::GeoTiffImportOptions& g) {
  if (!o.imageryNir.empty() || o.nirBand > 0) {
    datasets::NirInput nir;
    nir.file = o.imageryNir;
    nir.band = std::max(o.nirBand, 1);
    if (o.imageryNir.empty()) {  // --nir-band alone: a band of the imagery file itself
      if (o.imagery.size() != 1)
        return userError("--nir-band without --imagery-nir takes the band from --imagery FILE: give one file");
      nir.file = o.imagery[0];
    }
    if (Status s = crsOption("--imagery-nir-crs", o.imageryNirCrs, nir.assumeCrs); !s) return s;
    g.nir = std::move(nir);
  } else if (!o.imageryNirCrs.empty()) {
    return userError("--imagery-nir-crs states the CRS of --imagery-nir FILE, which was not given");
  }
  return {};
}

// --landcover, --landcover-scheme, --landcover-crs.
Status landcoverOptions(const ImportOptions& o, datasets::GeoTiffImportOptions& g) {
  if (!o.landcover.empty()) {
    datasets::GeoTiffImportOptions::Landcover l;
    l.file = o.landcover;
    auto scheme = datasets::parseLandcoverScheme(o.landcoverScheme);
    if (!scheme) return scheme.error();
    l.scheme = *scheme;
    if (Status s = crsOption("--landcover-crs", o.landcoverCrs, l.crs); !s) return s;
    g.landcover = std::move(l);
  } else if (!o.landcoverCrs.empty() || o.landcoverScheme != "auto") {
    return userError("--landcover-scheme and --landcover-crs describe --landcover FILE, which was not given");
  }
  return {};
}

// --canopy-height, --canopy-height-crs.
Status canopyOptions(const ImportOptions& o, datasets::GeoTiffImportOptions& g) {
  if (!o.canopyHeight.empty()) {
    datasets::GeoTiffImportOptions::Canopy c;
    c.file = o.canopyHeight;
    if (Status s = crsOption("--canopy-height-crs", o.canopyHeightCrs, c.crs); !s) return s;
    g.canopy = std::move(c);
  } else if (!o.canopyHeightCrs.empty()) {
    return userError("--canopy-height-crs states the CRS of --canopy-height FILE, which was not given");
  }
  return {};
}

// The output: --encoding, --imagery-format, --out, --name, --attribution, the zooms,
// --height-resampling, --memory-mb, --resume, --threads.
Status outputOptions(const ImportOptions& o, datasets::GeoTiffImportOptions& g) {
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
  return {};
}

}  // namespace

Result<datasets::GeoTiffImportOptions> geoTiffImportOptions(const ImportOptions& o, const std::atomic<bool>* cancel) {
  datasets::GeoTiffImportOptions g;
  // In this order, stopping at the first problem: the one reported.
  for (Status (*part)(const ImportOptions&, datasets::GeoTiffImportOptions&) :
       {demOptions, imageryOptions, radiometryOptions, nirOptions, landcoverOptions, canopyOptions, outputOptions})
    if (Status s = part(o, g); !s) return s.error();
  g.cancel = cancel;
  return g;
}

Result<datasets::XyzImportOptions> xyzImportOptions(const ImportOptions& o, const std::atomic<bool>* cancel) {
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
  x.cancel = cancel;
  return x;
}

}  // namespace vegstream::app
