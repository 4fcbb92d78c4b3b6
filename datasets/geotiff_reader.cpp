#include "datasets/geotiff_reader.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <OpenImageIO/imageio.h>

#include "datasets/geokeys.h"
#include "datasets/tiff_directory.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

// OpenImageIO 2.4 drops every GeoTIFF tag (its TIFF reader keeps only baseline/EXIF fields),
// so these are read from the file's first directory by tiff_directory.cpp; OIIO opens the file
// and decodes the pixels, which covers every compression and layout libtiff knows.
constexpr uint16_t kGeoTags[] = {tifftag::kImageWidth,      tifftag::kImageLength,         tifftag::kModelPixelScale,
                                 tifftag::kModelTiepoint,   tifftag::kModelTransformation, tifftag::kGeoKeyDirectory,
                                 tifftag::kGeoDoubleParams, tifftag::kGeoAsciiParams,      tifftag::kGdalNodata};

// Built by appending: GCC 12 at -O3 gives a false -Wrestrict on "'" + std::string (bug 105651).
std::string quoted(const fs::path& path) {
  std::string s(1, '\'');
  s += path.string();
  s += '\'';
  return s;
}

Error invalid(const fs::path& path, const std::string& what) {
  return makeError(ErrorKind::InvalidInput, quoted(path) + " " + what);
}

// OIIO's messages can span lines; one line keeps the user's error a single sentence.
std::string firstLine(std::string s) {
  if (auto nl = s.find('\n'); nl != std::string::npos) s.resize(nl);
  return s.empty() ? "unknown error" : s;
}

bool allFinite(const std::vector<double>& v, size_t n) {
  if (v.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// The affine transform from the tie point + pixel scale, or from the 4x4 model transformation.
Result<std::array<double, 6>> readTransform(const fs::path& path, const TiffDirectory& dir) {
  const TiffTagValue* scale = dir.find(tifftag::kModelPixelScale);
  const TiffTagValue* tie = dir.find(tifftag::kModelTiepoint);
  const TiffTagValue* matrix = dir.find(tifftag::kModelTransformation);
  if (scale && tie) {
    // Tie point (I, J, K, X, Y, Z): raster (I, J) lies at model (X, Y). Rows run south, so
    // the y scale, stored positive, is subtracted. Extra tie points (Goleta has four corner
    // ones) are consistent with the first when a pixel scale is given; the first suffices.
    if (!allFinite(scale->numbers, 2) || !allFinite(tie->numbers, 6) || scale->numbers[0] == 0 ||
        scale->numbers[1] == 0)
      return invalid(path, "has an unusable tie point or pixel scale (zero, NaN or too short)");
    const double sx = scale->numbers[0], sy = scale->numbers[1];
    const double i = tie->numbers[0], j = tie->numbers[1];
    const double x = tie->numbers[3], y = tie->numbers[4];
    return std::array<double, 6>{x - i * sx, sx, 0.0, y + j * sy, 0.0, -sy};
  }
  if (matrix) {
    // Row-major 4x4: x = m0·col + m1·row + m3,  y = m4·col + m5·row + m7.
    const auto& m = matrix->numbers;
    if (!allFinite(m, 16)) return invalid(path, "has an unusable ModelTransformation tag");
    const std::array<double, 6> t{m[3], m[0], m[1], m[7], m[4], m[5]};
    if (t[1] * t[5] - t[2] * t[4] == 0) return invalid(path, "has a degenerate ModelTransformation (zero determinant)");
    return t;
  }
  if (tie && tie->numbers.size() > 6)
    return makeError(ErrorKind::Unsupported, quoted(path) +
                                                 " is georeferenced by ground control points only (no pixel "
                                                 "scale); warp it to a regular grid first (e.g. gdalwarp)");
  return invalid(path,
                 "has no georeference (no tie point + pixel scale and no model "
                 "transformation)");
}

std::string crsHint(const std::string& problem, const fs::path& path) {
  return quoted(path) + " " + problem +
         "; its tie point and pixel scale are sound, so state the CRS yourself with --dem-crs "
         "(or --imagery-crs for imagery), e.g. --dem-crs EPSG:4326";
}

Result<GeoReference> readGeoReference(const fs::path& path, const TiffDirectory& dir, const ReadOptions& options) {
  auto transform = readTransform(path, dir);
  if (!transform) return transform.error();
  GeoReference geo;
  geo.transform = *transform;

  std::optional<GeoKeys> keys;
  if (const TiffTagValue* keyDir = dir.find(tifftag::kGeoKeyDirectory)) {
    static const std::vector<double> kNone;
    const TiffTagValue* doubles = dir.find(tifftag::kGeoDoubleParams);
    const TiffTagValue* ascii = dir.find(tifftag::kGeoAsciiParams);
    keys = decodeGeoKeys(keyDir->numbers, doubles ? doubles->numbers : kNone, ascii ? ascii->text : std::string());
    if (!keys && !options.assumeEpsg)
      return makeError(ErrorKind::InvalidInput,
                       crsHint("has a corrupt GeoKey directory, so its CRS cannot be read", path));
  } else if (!options.assumeEpsg) {
    return makeError(ErrorKind::InvalidInput, crsHint("has no GeoKey directory, so its CRS is unknown", path));
  }

  if (keys) {
    geo.epsg = keys->epsg();
    geo.crsDescription = keys->description();
    if (keys->rasterType == 2) geo.rasterType = RasterType::PixelIsPoint;
  }
  if (options.assumeEpsg) {
    geo.epsg = *options.assumeEpsg;
    geo.crsDescription = "EPSG:" + std::to_string(*options.assumeEpsg) + " (stated by the user)";
  }
  if (geo.rasterType == RasterType::PixelIsPoint) {
    // The tie point names the first pixel's centre; move the origin half a pixel back so the
    // transform maps pixel corners, as GDAL does.
    auto& t = geo.transform;
    t[0] -= 0.5 * (t[1] + t[2]);
    t[3] -= 0.5 * (t[4] + t[5]);
  }
  return geo;
}

Result<std::optional<double>> readNodata(const fs::path& path, const TiffDirectory& dir, const ReadOptions& options) {
  std::optional<double> value = options.nodataOverride;
  if (!value) {
    const TiffTagValue* tag = dir.find(tifftag::kGdalNodata);
    if (!tag) return std::optional<double>{};
    const std::string text = tag->text.c_str();  // stops at the terminating NUL
    char* end = nullptr;
    const double parsed = std::strtod(text.c_str(), &end);
    while (end && *end == ' ') ++end;
    if (text.empty() || end == text.c_str() || (end && *end != '\0'))
      return invalid(path, "has a GDAL_NODATA tag that is not a number: '" + text + "'");
    value = parsed;
  }
  // Samples are stored as float; comparing against the float-rounded value makes nodata such
  // as -3.40282e+38 (written with few digits) match the samples that hold it.
  if (std::isfinite(*value)) value = static_cast<double>(static_cast<float>(*value));
  return value;
}

template <typename T>
void widen(const std::vector<unsigned char>& raw, std::vector<float>& out) {
  for (size_t i = 0; i < out.size(); ++i) {
    T v;
    std::memcpy(&v, &raw[i * sizeof(T)], sizeof(T));
    out[i] = static_cast<float>(v);
  }
}

// Pixels as float holding the raw digital numbers. OIIO's own conversion to FLOAT would
// normalise integer types to 0..1, so integers are read in their native type and widened here.
Status readPixels(const fs::path& path, OIIO::ImageInput& in, Raster& raster) {
  const OIIO::ImageSpec& spec = in.spec();
  const size_t count =
      static_cast<size_t>(raster.width) * static_cast<size_t>(raster.height) * static_cast<size_t>(raster.channels);
  raster.samples.assign(count, 0.0f);
  const auto base = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
  const bool floating = base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::DOUBLE;
  std::vector<unsigned char> raw;
  void* target = raster.samples.data();
  OIIO::TypeDesc type = OIIO::TypeDesc::FLOAT;
  if (!floating) {
    raw.resize(count * spec.format.size());
    target = raw.data();
    type = spec.format;
  }
  if (!in.read_image(0, 0, 0, raster.channels, type, target))
    return invalid(path, "cannot be read, it is probably truncated or corrupt (" + firstLine(in.geterror()) + ")");
  switch (base) {
    case OIIO::TypeDesc::UINT8: widen<uint8_t>(raw, raster.samples); break;
    case OIIO::TypeDesc::INT8: widen<int8_t>(raw, raster.samples); break;
    case OIIO::TypeDesc::UINT16: widen<uint16_t>(raw, raster.samples); break;
    case OIIO::TypeDesc::INT16: widen<int16_t>(raw, raster.samples); break;
    case OIIO::TypeDesc::UINT32: widen<uint32_t>(raw, raster.samples); break;
    case OIIO::TypeDesc::INT32: widen<int32_t>(raw, raster.samples); break;
    case OIIO::TypeDesc::UINT64: widen<uint64_t>(raw, raster.samples); break;
    case OIIO::TypeDesc::INT64: widen<int64_t>(raw, raster.samples); break;
    default: break;  // floating types were converted by OIIO, without normalisation
  }
  return {};
}

// Refuses empty rasters and ones above ReadOptions::maxPixels, before anything is allocated.
Status checkSize(const fs::path& path, double width, double height, const ReadOptions& options) {
  const auto text = [](double v) { return std::to_string(static_cast<long long>(v)); };
  if (!(width >= 1 && height >= 1)) return invalid(path, "has no pixels (" + text(width) + " x " + text(height) + ")");
  const double pixels = width * height;  // exact: both fit in 32 bits
  if (pixels > static_cast<double>(options.maxPixels))
    return invalid(path, "is too large: " + text(width) + " x " + text(height) + " = " + text(pixels) +
                             " pixels, more than the limit of " + std::to_string(options.maxPixels));
  return {};
}

bool isSupportedType(const OIIO::TypeDesc& t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8:
    case OIIO::TypeDesc::INT8:
    case OIIO::TypeDesc::UINT16:
    case OIIO::TypeDesc::INT16:
    case OIIO::TypeDesc::UINT32:
    case OIIO::TypeDesc::INT32:
    case OIIO::TypeDesc::UINT64:
    case OIIO::TypeDesc::INT64:
    case OIIO::TypeDesc::HALF:
    case OIIO::TypeDesc::FLOAT:
    case OIIO::TypeDesc::DOUBLE: return t.aggregate == OIIO::TypeDesc::SCALAR && t.arraylen == 0;
    default: return false;
  }
}

}  // namespace

Result<Raster> readGeoTiff(const fs::path& path, const ReadOptions& options) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return makeError(ErrorKind::NotFound, "GeoTIFF file " + quoted(path) + " does not exist");
  if (!fs::is_regular_file(path, ec)) return invalid(path, "is not a regular file");

  // The directory is read first: it says "not a TIFF" plainly and gives the size before OIIO
  // (whose own limit is 32 GB) is asked to open anything.
  auto dir = readFirstTiffDirectory(path, kGeoTags);
  if (!dir) return dir.error();
  const TiffTagValue* w = dir->find(tifftag::kImageWidth);
  const TiffTagValue* h = dir->find(tifftag::kImageLength);
  if (w && h && !w->numbers.empty() && !h->numbers.empty())
    if (Status s = checkSize(path, w->numbers[0], h->numbers[0], options); !s) return s.error();

  auto in = OIIO::ImageInput::open(path.string());
  if (!in) return invalid(path, "cannot be opened as an image (" + firstLine(OIIO::geterror()) + ")");
  if (std::string(in->format_name()) != "tiff")
    return invalid(path, "is a " + std::string(in->format_name()) + " file, not a TIFF");

  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels <= 0) return invalid(path, "has no channels");
  if (Status s = checkSize(path, spec.width, spec.height, options); !s) return s.error();
  if (spec.depth > 1 || !spec.channelformats.empty() || !isSupportedType(spec.format))
    return makeError(ErrorKind::Unsupported, quoted(path) + " has a sample layout vegstream cannot read (" +
                                                 std::string(spec.format.c_str()) +
                                                 (spec.channelformats.empty() ? "" : ", per-channel types") +
                                                 (spec.depth > 1 ? ", volume" : "") + ")");

  auto geo = readGeoReference(path, *dir, options);
  if (!geo) return geo.error();
  auto nodata = readNodata(path, *dir, options);
  if (!nodata) return nodata.error();

  Raster raster;
  raster.path = path;
  raster.width = spec.width;
  raster.height = spec.height;
  raster.channels = spec.nchannels;
  raster.nodata = *nodata;
  raster.georef = std::move(*geo);
  if (Status s = readPixels(path, *in, raster); !s) return s.error();
  return raster;
}

}  // namespace vegstream::datasets
