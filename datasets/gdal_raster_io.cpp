// Windows, masks, units and acquisition time through GDAL (gdal_raster_io.h).

#include "datasets/gdal_raster_io.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <regex>

namespace vegstream::datasets {
namespace {

constexpr double kFootM = 0.3048;
constexpr double kUsSurveyFootM = 1200.0 / 3937.0;

std::string lower(const char* s) {
  std::string t = s ? s : "";
  for (char& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return t;
}

GDALRasterIOExtraArg nearest() {
  GDALRasterIOExtraArg a;
  INIT_RASTERIO_EXTRA_ARG(a);
  a.eResampleAlg = GRIORA_NearestNeighbour;
  return a;
}

// NaN where band b's mask says no data.
Status applyMask(GDALRasterBand& band, const PixelWindow& win, size_t channel, Raster& out) {
  const int flags = band.GetMaskFlags();
  if (flags & GMF_ALL_VALID) return {};
  GDALRasterBand* mask = band.GetMaskBand();
  if (!mask) return {};
  std::vector<uint8_t> m(static_cast<size_t>(out.width) * static_cast<size_t>(out.height));
  GDALRasterIOExtraArg arg = nearest();
  if (mask->RasterIO(GF_Read, win.x0, win.y0, win.w, win.h, m.data(), out.width, out.height, GDT_Byte, 0, 0, &arg) !=
      CE_None)
    return makeError(ErrorKind::InvalidInput, "cannot read its mask");
  const size_t n = static_cast<size_t>(out.channels);
  for (size_t p = 0; p < m.size(); ++p)
    if (m[p] == 0) out.samples[p * n + channel] = NAN;
  return {};
}

}  // namespace

Status readWindow(GDALDataset& d, const std::vector<int>& bands, const std::vector<double>& scale,
                  const std::vector<double>& offset, std::optional<double> nodataOverride, double verticalScale,
                  const PixelWindow& win, Raster& out) {
  const size_t n = bands.size();
  GDALRasterIOExtraArg arg = nearest();
  const auto pixelSpace = static_cast<GSpacing>(n * sizeof(float));
  for (size_t b = 0; b < n; ++b) {
    GDALRasterBand* band = d.GetRasterBand(bands[b]);
    if (!band) return makeError(ErrorKind::InvalidInput, "a band disappeared");
    if (band->RasterIO(GF_Read, win.x0, win.y0, win.w, win.h, out.samples.data() + b, out.width, out.height,
                       GDT_Float32, pixelSpace, pixelSpace * out.width, &arg) != CE_None)
      return makeError(ErrorKind::InvalidInput, "cannot read its pixels (truncated or corrupt)");
    if (!nodataOverride) {
      if (auto s = applyMask(*band, win, b, out); !s) return s;
    }
  }
  const size_t count = static_cast<size_t>(out.width) * static_cast<size_t>(out.height);
  for (size_t p = 0; p < count; ++p)
    for (size_t b = 0; b < n; ++b) {
      float& v = out.samples[p * n + b];
      if (nodataOverride && static_cast<double>(v) == *nodataOverride) v = NAN;
      if (std::isnan(v) || (scale[b] == 1.0 && offset[b] == 0.0 && verticalScale == 1.0)) continue;
      v = static_cast<float>((v * scale[b] + offset[b]) * verticalScale);
    }
  return {};
}

double bandUnitScale(const char* unit, double current) {
  const std::string u = lower(unit);
  if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return kFootM;
  if (u == "us survey foot" || u == "ftus" || u == "us-ft" || u == "foot_us" || u == "us_survey_foot")
    return kUsSurveyFootM;
  if (u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters") return 1.0;
  return current;
}

double verticalUnitScale(const OGRSpatialReference& srs, double current) {
  if (!srs.IsCompound() && !srs.IsVertical()) return current;
  const char* name = nullptr;
  const double toMetres = srs.GetTargetLinearUnits("VERT_CS", &name);
  return toMetres > 0.0 ? toMetres : current;
}

std::optional<std::string> acquisitionDatetimeOf(GDALDataset& d) {
  // GDAL's IMAGERY domain (from IMD / RPC / DIMAP side-cars): "YYYY-MM-DD HH:MM:SS", UTC.
  if (const char* t = d.GetMetadataItem("ACQUISITIONDATETIME", "IMAGERY")) {
    static const std::regex iso(R"((\d{4}-\d{2}-\d{2})[ T](\d{2}:\d{2}:\d{2})(?:\.\d+)?Z?)");
    std::cmatch m;
    if (std::regex_match(t, m, iso)) return m[1].str() + "T" + m[2].str() + "Z";
  }
  // EXIF (drone photographs): the local time with its offset; without the offset it is unknown.
  const char* t = d.GetMetadataItem("EXIF_DateTimeOriginal");
  const char* z = d.GetMetadataItem("EXIF_OffsetTimeOriginal");
  if (t && z) {
    static const std::regex exif(R"((\d{4}):(\d{2}):(\d{2}) (\d{2}:\d{2}:\d{2}))");
    static const std::regex zone(R"([+-]\d{2}:\d{2})");
    std::cmatch m;
    if (std::regex_match(t, m, exif) && std::regex_match(z, zone))
      return m[1].str() + "-" + m[2].str() + "-" + m[3].str() + "T" + m[4].str() + z;
  }
  return std::nullopt;
}

}  // namespace vegstream::datasets
