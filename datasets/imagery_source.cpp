// Reading and normalising imagery for the importer (imagery_source.h): bands merged, nodata
// made NaN, digital numbers turned into reflectance (radiometry.h) or stretched to 0 … 255.

#include "datasets/imagery_source.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <regex>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

bool sameGrid(const Raster& a, const Raster& b) {
  return a.width == b.width && a.height == b.height && a.georef.epsg == b.georef.epsg &&
         a.georef.transform == b.georef.transform;
}

// One RGB(A) / grey file or three single-band files → a 3-channel raster of raw values with
// NaN for nodata (a pixel is nodata when every channel holds the nodata value, or alpha is 0).
Result<Raster> readMerged(const ImageryInput& in) {
  ReadOptions ro;
  ro.assumeEpsg = in.assumeEpsg;
  ro.maxPixels = in.maxPixels;
  Raster out;
  if (in.file) {
    auto r = readGeoTiff(*in.file, ro);
    if (!r) return r.error();
    Raster& src = *r;
    const int n = src.channels;
    out = src;
    out.channels = 3;
    out.samples.assign(static_cast<size_t>(src.width) * static_cast<size_t>(src.height) * 3, NAN);
    for (size_t p = 0, count = static_cast<size_t>(src.width) * static_cast<size_t>(src.height); p < count; ++p) {
      const float* s = &src.samples[p * static_cast<size_t>(n)];
      const bool grey = n <= 2;
      const bool alphaZero = (n == 2 && s[1] == 0) || (n >= 4 && s[3] == 0);
      bool allNodata = true;
      for (int c = 0; c < std::min(n, 3); ++c) allNodata = allNodata && src.isNodata(s[c]);
      if (alphaZero || allNodata) continue;
      for (size_t c = 0; c < 3; ++c) out.samples[p * 3 + c] = grey ? s[0] : s[c];
    }
    out.nodata.reset();
    return out;
  }
  std::vector<Raster> bands;
  for (const auto& path : in.bands) {
    auto r = readGeoTiff(path, ro);
    if (!r) return r.error();
    if (r->channels != 1)
      return makeError(ErrorKind::InvalidInput,
                       concat(path, " has ", r->channels, " channels; each --imagery-bands file must hold one band"));
    if (!bands.empty() && !sameGrid(bands.front(), *r))
      return makeError(ErrorKind::InvalidInput,
                       concat(path, " is not on the same grid (size, transform, CRS) as ", bands.front().path,
                              "; --imagery-bands files must share one grid"));
    bands.push_back(std::move(*r));
  }
  out = bands.front();
  out.path = bands.front().path;
  out.channels = 3;
  const size_t count = static_cast<size_t>(out.width) * static_cast<size_t>(out.height);
  out.samples.assign(count * 3, NAN);
  for (size_t p = 0; p < count; ++p) {
    bool anyNodata = false;
    for (size_t c = 0; c < 3; ++c) anyNodata = anyNodata || bands[c].isNodata(bands[c].samples[p]);
    if (anyNodata) continue;
    for (size_t c = 0; c < 3; ++c) out.samples[p * 3 + c] = bands[c].samples[p];
  }
  out.nodata.reset();
  return out;
}

}  // namespace

Result<Stretch> parseStretch(const std::string& text) {
  static const std::regex pct(R"(\s*[pP](\d+(?:\.\d*)?)\s*,\s*[pP](\d+(?:\.\d*)?)\s*)");
  static const std::regex fixed(R"(\s*(-?\d+(?:\.\d*)?)\s*,\s*(-?\d+(?:\.\d*)?)\s*)");
  std::smatch m;
  Stretch s;
  if (std::regex_match(text, m, pct)) {
    s.kind = Stretch::Kind::Percentile;
    s.lo = std::stod(m[1]);
    s.hi = std::stod(m[2]);
    if (s.lo < s.hi && s.hi <= 100.0) return s;
  } else if (std::regex_match(text, m, fixed)) {
    s.kind = Stretch::Kind::Fixed;
    s.lo = std::stod(m[1]);
    s.hi = std::stod(m[2]);
    if (s.lo < s.hi) return s;
  }
  return makeError(ErrorKind::InvalidInput, concat("--stretch '", text,
                                                   "': expected percentiles pLO,pHI (e.g. p1,p99, LO < HI ≤ 100) or "
                                                   "sample values LO,HI with LO < HI (e.g. 6700,18300)"));
}

namespace {

// Extremes, 1st / 99th percentiles and integrality of the valid samples of all three channels.
ImageryValues valuesOf(const Raster& r) {
  ImageryValues v{INFINITY, -INFINITY, 0.0, 0.0, true};
  std::vector<float> all;
  all.reserve(r.samples.size());
  for (size_t p = 0; p + 2 < r.samples.size(); p += 3) {
    if (std::isnan(r.samples[p])) continue;
    for (size_t c = 0; c < 3; ++c) {
      const float x = r.samples[p + c];
      v.lo = std::min(v.lo, x);
      v.hi = std::max(v.hi, x);
      v.integers = v.integers && x == std::floor(x);
      all.push_back(x);
    }
  }
  if (all.empty()) return v;
  v.p1 = percentile(all, 1.0);
  v.p99 = percentile(all, 99.0);
  return v;
}

// Each band between its stretch range onto 0 … 255 (out.ranges).
void applyStretch(const Stretch& stretch, PreparedImagery& out) {
  Raster& r = out.raster;
  const size_t count = static_cast<size_t>(r.width) * static_cast<size_t>(r.height);
  for (size_t c = 0; c < 3; ++c) {
    double a = stretch.lo, b = stretch.hi;
    if (stretch.kind == Stretch::Kind::Percentile) {
      std::vector<float> values;
      for (size_t p = 0; p < count; ++p)
        if (!std::isnan(r.samples[p * 3 + c])) values.push_back(r.samples[p * 3 + c]);
      a = percentile(values, stretch.lo);
      b = percentile(values, stretch.hi);
      if (!(b > a)) b = a + 1.0;  // a flat band: everything at or above a is white
    }
    out.ranges[c] = {a, b};
    const double scale = 255.0 / (b - a);
    for (size_t p = 0; p < count; ++p) {
      float& v = r.samples[p * 3 + c];
      if (!std::isnan(v)) v = static_cast<float>(std::clamp((v - a) * scale, 0.0, 255.0));
    }
  }
  out.stretched = true;
  out.description =
      concat("stretched R ", out.ranges[0][0], "…", out.ranges[0][1], ", G ", out.ranges[1][0], "…", out.ranges[1][1],
             ", B ", out.ranges[2][0], "…", out.ranges[2][1], " (display colours, not albedo)");
}

void applyReflectance(const RadiometryChoice& choice, PreparedImagery& out) {
  const std::array<double, 3> dark = toSurfaceReflectance(out.raster.samples, choice.scale, choice.offset);
  out.linear = true;
  RadiometryRecord& rec = out.radiometry;
  rec.scale = choice.scale;
  rec.offset = choice.offset;
  rec.darkObject = dark;
  rec.darkObjectPercentile = kDarkObjectPercent;
  rec.darkObjectReflectance = kDarkObjectReflectance;
  out.description = concat("surface reflectance DN x ", choice.scale, " + ", choice.offset,
                           ", dark-object subtracted (dark objects R ", dark[0], ", G ", dark[1], ", B ", dark[2], ")");
}

}  // namespace

Result<PreparedImagery> prepareImagery(const ImageryInput& input, const Logger& /*log*/) {
  assert(input.file.has_value() != !input.bands.empty());
  auto merged = readMerged(input);
  if (!merged) return merged.error();
  PreparedImagery out;
  out.raster = std::move(*merged);
  Raster& r = out.raster;
  const ImageryValues values = valuesOf(r);
  if (!(values.lo <= values.hi))
    return makeError(ErrorKind::InvalidInput, concat(r.path, " has no valid imagery pixel (all nodata)"));
  std::vector<fs::path> files = input.bands;
  if (input.file) files = {*input.file};
  auto choice = chooseRadiometry(input.radiometry, input.stretch.has_value(), files, values);
  if (!choice) return choice.error();
  out.radiometryChoice = concat("radiometry ", toString(choice->method), " (", choice->why, ")");
  if (input.keepRawRed) {
    const size_t count = static_cast<size_t>(r.width) * static_cast<size_t>(r.height);
    out.rawRed.resize(count);
    for (size_t p = 0; p < count; ++p) out.rawRed[p] = r.samples[p * 3];
  }
  out.radiometry.method = toString(choice->method);
  if (choice->method == RadiometryMethod::Reflectance) {
    applyReflectance(*choice, out);
  } else if (choice->method == RadiometryMethod::Stretch) {
    applyStretch(input.stretch.value_or(Stretch{}), out);
  } else {
    out.description = "8-bit sRGB colour as stored";
  }
  return out;
}

}  // namespace vegstream::datasets
