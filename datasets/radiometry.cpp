// Radiometry of imported imagery (radiometry.h).
//
// Dark-object subtraction: P. S. Chavez Jr., "An improved dark-object subtraction technique for
// atmospheric scattering correction of multispectral data", Remote Sensing of Environment 24,
// 459–479, 1988; the 1 % reflectance of the darkest object: P. S. Chavez Jr., "Image-based
// atmospheric corrections — revisited and improved", PE&RS 62(9), 1025–1036, 1996 (DOS1).
// Landsat scaling: USGS Landsat 8-9 OLI/TIRS Collection 2 Level-1 and Level-2 Data Format
// Control Books (REFLECTANCE_MULT_BAND_n = 2.0e-5, REFLECTANCE_ADD_BAND_n = −0.1; surface
// reflectance 2.75e-5, −0.2).

#include "datasets/radiometry.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <regex>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Whether reflectances at the 1st and 99th percentiles are those of the earth's surface.
bool plausibleReflectance(const ImageryValues& v, double scale, double offset) {
  const double r1 = v.p1 * scale + offset, r99 = v.p99 * scale + offset;
  return v.integers && v.lo >= 0.0f && v.hi <= 65535.0f && r1 >= -0.05 && r99 > 0.0 && r99 <= 1.2;
}

std::string fileList(const std::vector<fs::path>& files) {
  std::string s;
  for (const auto& f : files) {
    if (!s.empty()) s += ',';
    s += f.filename().string();
  }
  return s;
}

}  // namespace

const char* toString(RadiometryMethod m) {
  switch (m) {
    case RadiometryMethod::Auto: return "auto";
    case RadiometryMethod::Reflectance: return "reflectance";
    case RadiometryMethod::Srgb: return "srgb";
    case RadiometryMethod::Stretch: return "stretch";
  }
  return "auto";
}

Result<RadiometryMethod> parseRadiometryMethod(const std::string& text) {
  for (auto m :
       {RadiometryMethod::Auto, RadiometryMethod::Reflectance, RadiometryMethod::Srgb, RadiometryMethod::Stretch})
    if (text == toString(m)) return m;
  return makeError(ErrorKind::InvalidInput,
                   concat("--radiometry '", text, "': expected auto, reflectance, srgb or stretch"));
}

LandsatLevel landsatFromNames(const std::vector<fs::path>& files) {
  // Collection product ids (LC08_L1TP_038034_20150818_…, LE07_L2SP_…), pre-collection scene
  // ids (LC80380342015230LGN00), or the word.
  static const std::regex product(R"((^|[^a-z0-9])l[cote]0[4-9]_l[12])");
  static const std::regex scene(R"((^|[^a-z0-9])l[cote][4-9]\d{13}[a-z]{3}\d{2})");
  static const std::regex level2(R"(l2sp|l2sr|_sr_b)");
  LandsatLevel level = LandsatLevel::None;
  for (const auto& f : files) {
    const std::string name = lower(f.filename().string()), dir = lower(f.parent_path().filename().string());
    for (const std::string& s : {name, dir}) {
      if (s.empty()) continue;
      const bool landsat =
          std::regex_search(s, product) || std::regex_search(s, scene) || s.find("landsat") != std::string::npos;
      if (!landsat) continue;
      if (std::regex_search(s, level2)) return LandsatLevel::Level2;
      level = LandsatLevel::Level1;
    }
  }
  return level;
}

Result<RadiometryChoice> chooseRadiometry(const RadiometryOptions& o, bool stretchGiven,
                                          const std::vector<fs::path>& files, const ImageryValues& v) {
  const bool eightBit = v.lo >= 0.0f && v.hi <= 255.0f;
  RadiometryChoice c;
  const LandsatLevel landsat = landsatFromNames(files);
  if (landsat == LandsatLevel::Level2) {
    c.scale = kLandsatL2ReflectanceScale;
    c.offset = kLandsatL2ReflectanceOffset;
  }
  c.scale = o.scale.value_or(c.scale);
  c.offset = o.offset.value_or(c.offset);
  c.method = o.method;
  if (stretchGiven && (o.method == RadiometryMethod::Reflectance || o.method == RadiometryMethod::Srgb))
    return makeError(ErrorKind::InvalidInput, concat("--stretch goes with --radiometry stretch (or auto), not with "
                                                     "--radiometry ",
                                                     toString(o.method)));
  if (o.method == RadiometryMethod::Srgb && !eightBit)
    return makeError(ErrorKind::InvalidInput,
                     concat("--radiometry srgb: ", fileList(files), " holds values ", v.lo, " … ", v.hi,
                            ", not 8-bit sRGB; use --radiometry reflectance or stretch"));
  if (o.method != RadiometryMethod::Auto) {
    c.why = concat("--radiometry ", toString(o.method));
    return c;
  }
  if (stretchGiven) {
    c.method = RadiometryMethod::Stretch;
    c.why = "--stretch given";
  } else if (eightBit) {
    c.method = RadiometryMethod::Srgb;
    c.why = "8-bit values: taken as sRGB-encoded";
  } else if (landsat != LandsatLevel::None && plausibleReflectance(v, c.scale, c.offset)) {
    c.method = RadiometryMethod::Reflectance;
    c.why = concat("Landsat ", landsat == LandsatLevel::Level2 ? "Level-2" : "Level-1",
                   " digital numbers by their names and values: reflectance = DN x ", c.scale, " + ", c.offset);
  } else {
    c.method = RadiometryMethod::Stretch;
    c.why =
        landsat != LandsatLevel::None
            ? concat("named like Landsat but values ", v.lo, " … ", v.hi,
                     " do not scale to reflectances: stretching p1,p99 (display colours, not albedo)")
            : concat("values ", v.lo, " … ", v.hi,
                     " exceed 8 bits and are not a known sensor's: stretching p1,p99 (display colours, not "
                     "albedo; --radiometry reflectance with --reflectance-scale/--reflectance-offset gives albedo)");
  }
  return c;
}

double percentile(std::vector<float>& values, double p) {
  const size_t k = static_cast<size_t>(std::llround(p / 100.0 * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

std::array<double, 3> darkObjects(const std::vector<float>& rgb, double scale, double offset) {
  std::array<double, 3> dark{};
  const size_t count = rgb.size() / 3;
  std::vector<float> band;
  band.reserve(count);
  for (size_t c = 0; c < 3; ++c) {
    band.clear();
    for (size_t p = 0; p < count; ++p) {
      const float v = rgb[p * 3 + c];
      if (!std::isnan(v)) band.push_back(static_cast<float>(static_cast<double>(v) * scale + offset));
    }
    if (!band.empty()) dark[c] = percentile(band, kDarkObjectPercent);
  }
  return dark;
}

void applySurfaceReflectance(std::vector<float>& rgb, double scale, double offset, const std::array<double, 3>& dark) {
  const size_t count = rgb.size() / 3;
  for (size_t c = 0; c < 3; ++c) {
    const double haze = std::max(0.0, dark[c] - kDarkObjectReflectance);
    for (size_t p = 0; p < count; ++p) {
      float& v = rgb[p * 3 + c];
      if (std::isnan(v)) continue;
      const auto r = static_cast<float>(static_cast<double>(v) * scale + offset);
      v = static_cast<float>(std::clamp(static_cast<double>(r) - haze, 0.0, 1.0));
    }
  }
}

std::array<double, 3> toSurfaceReflectance(std::vector<float>& rgb, double scale, double offset) {
  const std::array<double, 3> dark = darkObjects(rgb, scale, offset);
  applySurfaceReflectance(rgb, scale, offset, dark);
  return dark;
}

}  // namespace vegstream::datasets
