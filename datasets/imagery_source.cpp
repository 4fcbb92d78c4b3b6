// Reading and normalising imagery for the importer, window by window (imagery_source.h): bands merged, nodata
// made NaN, digital numbers turned into reflectance (radiometry.h) or stretched to 0 … 255.

#include "datasets/imagery_source.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <regex>

#include "datasets/message.h"
#include "datasets/srgb.h"

namespace vegstream::datasets {
namespace {
namespace fs = std::filesystem;

bool sameGrid(const RasterSource& a, const RasterSource& b) {
  return a.width() == b.width() && a.height() == b.height() && a.crs() == b.crs() &&
         a.georef().transform == b.georef().transform;
}

Result<std::vector<RasterSource>> openSources(const ImageryInput& in) {
  SourceOptions so;
  so.flag = in.files.empty() ? "--imagery-bands" : "--imagery";
  so.crsFlag = "--imagery-crs";
  so.assumeCrs = in.assumeCrs;
  std::vector<RasterSource> out;
  if (!in.files.empty()) {
    so.bands = in.bandNumbers;
    if (!so.bands.empty() && so.bands.size() != 3 && so.bands.size() != 1)
      return makeError(ErrorKind::InvalidInput, "--bands takes three bands (R,G,B) or one (grey)");
    auto r = RasterSource::open(in.files, so);
    if (!r) return r.error();
    out.push_back(std::move(*r));
    return out;
  }
  for (const auto& path : in.bands) {
    auto r = RasterSource::open({path}, so);
    if (!r) return r.error();
    if (r->channels() != 1)
      return makeError(ErrorKind::InvalidInput,
                       concat(path, " has ", r->channels(), " bands; each --imagery-bands file must hold one band"));
    if (!out.empty() && !sameGrid(out.front(), *r))
      return makeError(ErrorKind::InvalidInput,
                       concat(path, " is not on the same grid (size, transform, CRS) as ", out.front().label(),
                              "; --imagery-bands files must share one grid"));
    out.push_back(std::move(*r));
  }
  return out;
}

// Each band's stretch range (out.ranges), from the overview's values.
void stretchRanges(const Stretch& stretch, const Raster& r, PreparedImagery& out) {
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
  }
  out.stretched = true;
  out.description =
      concat("stretched R ", out.ranges[0][0], "…", out.ranges[0][1], ", G ", out.ranges[1][0], "…", out.ranges[1][1],
             ", B ", out.ranges[2][0], "…", out.ranges[2][1], " (display colours, not albedo)");
}

}  // namespace

std::string ImageryInput::label() const { return files.empty() ? (bands.empty() ? "" : bands[0]) : files[0]; }

Raster PreparedImagery::merged(std::vector<Raster> parts) const {
  Raster out = parts.front();
  out.channels = 3;
  out.nodata.reset();
  const size_t count = static_cast<size_t>(out.width) * static_cast<size_t>(out.height);
  out.samples.assign(count * 3, NAN);
  if (parts.size() == 1) {
    const Raster& src = parts.front();
    const auto n = static_cast<size_t>(src.channels);
    for (size_t p = 0; p < count; ++p) {
      const float* v = &src.samples[p * n];
      const bool grey = n < 3;
      bool any = false;
      for (size_t c = 0; c < std::min<size_t>(n, 3); ++c) any = any || !std::isnan(v[c]);
      if (!any) continue;  // every channel no data (its mask, alpha or nodata value)
      for (size_t c = 0; c < 3; ++c) {
        const float x = grey ? v[0] : v[c];
        out.samples[p * 3 + c] = std::isnan(x) ? 0.0f : x;  // one band's nodata among valid ones: 0
      }
    }
    return out;
  }
  for (size_t p = 0; p < count; ++p) {
    bool anyNodata = false;
    for (size_t c = 0; c < 3; ++c) anyNodata = anyNodata || std::isnan(parts[c].samples[p]);
    if (anyNodata) continue;
    for (size_t c = 0; c < 3; ++c) out.samples[p * 3 + c] = parts[c].samples[p];
  }
  return out;
}

void PreparedImagery::convert(Raster& r) const {
  if (method_ == RadiometryMethod::Reflectance) {
    applySurfaceReflectance(r.samples, scale_, offset_, dark_);
    return;
  }
  if (method_ != RadiometryMethod::Stretch) return;
  const size_t count = static_cast<size_t>(r.width) * static_cast<size_t>(r.height);
  for (size_t c = 0; c < 3; ++c) {
    const double a = ranges[c][0], b = ranges[c][1], scale = 255.0 / (b - a);
    for (size_t p = 0; p < count; ++p) {
      float& v = r.samples[p * 3 + c];
      if (!std::isnan(v)) v = static_cast<float>(std::clamp((v - a) * scale, 0.0, 255.0));
    }
  }
}

Result<std::optional<ImageryWindow>> PreparedImagery::window(const SourceGrid& grid,
                                                             const std::vector<glm::dvec2>& pixels, int margin,
                                                             int maxSide) const {
  auto first = grid.windowFor(pixels, margin, maxSide);
  if (!first) return first.error();
  if (!*first) return std::optional<ImageryWindow>();
  std::vector<Raster> parts;
  parts.push_back(std::move(**first));
  const Raster& f = parts.front();
  const int x0 = static_cast<int>(f.origin.x), y0 = static_cast<int>(f.origin.y);
  const int w = static_cast<int>(std::lround(f.width * f.step.x)), h = static_cast<int>(std::lround(f.height * f.step.y));
  for (size_t k = 1; k < sources_.size(); ++k) {
    auto r = sources_[k].read(x0, y0, w, h, maxSide);
    if (!r) return r.error();
    parts.push_back(std::move(*r));
  }
  ImageryWindow out;
  out.colour = merged(std::move(parts));
  const size_t count = static_cast<size_t>(out.colour.width) * static_cast<size_t>(out.colour.height);
  out.rawRed.resize(count);
  for (size_t p = 0; p < count; ++p) out.rawRed[p] = out.colour.samples[p * 3];
  convert(out.colour);
  return std::optional<ImageryWindow>(std::move(out));
}

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

}  // namespace

// The colour calibration of the overview as the tiles will hold it: converted, in linear light.
ColourCalibrationRecord PreparedImagery::calibrationOf(const PreparedImagery& p, Raster overview) {
  p.convert(overview);
  if (!p.linear)
    for (float& v : overview.samples)
      if (!std::isnan(v)) v = srgbDecode(std::clamp(v, 0.0f, 255.0f) / 255.0f);
  return estimateColourCalibration(overview.samples);
}

Result<PreparedImagery> PreparedImagery::open(const ImageryInput& input, const Logger& /*log*/) {
  assert(input.files.empty() != input.bands.empty());
  auto sources = openSources(input);
  if (!sources) return sources.error();
  PreparedImagery out;
  out.sources_ = std::move(*sources);
  std::vector<Raster> parts;
  for (const RasterSource& src : out.sources_) {
    auto r = src.readOverview(kStatisticsPixels);
    if (!r) return r.error();
    parts.push_back(std::move(*r));
  }
  const Raster overview = out.merged(std::move(parts));
  const ImageryValues values = valuesOf(overview);
  if (!(values.lo <= values.hi))
    return makeError(ErrorKind::InvalidInput, concat(input.label(), " has no valid imagery pixel (all nodata)"));
  std::vector<fs::path> files;
  for (const auto& f : input.files.empty() ? input.bands : input.files) files.emplace_back(f);
  auto choice = chooseRadiometry(input.radiometry, input.stretch.has_value(), files, values);
  if (!choice) return choice.error();
  out.radiometryChoice = concat("radiometry ", toString(choice->method), " (", choice->why, ")");
  out.method_ = choice->method;
  out.radiometry.method = toString(choice->method);
  if (choice->method == RadiometryMethod::Reflectance) {
    out.scale_ = choice->scale;
    out.offset_ = choice->offset;
    out.dark_ = darkObjects(overview.samples, choice->scale, choice->offset);
    out.linear = true;
    RadiometryRecord& rec = out.radiometry;
    rec.scale = choice->scale;
    rec.offset = choice->offset;
    rec.darkObject = out.dark_;
    rec.darkObjectPercentile = kDarkObjectPercent;
    rec.darkObjectReflectance = kDarkObjectReflectance;
    out.description = concat("surface reflectance DN x ", choice->scale, " + ", choice->offset,
                             ", dark-object subtracted (dark objects R ", out.dark_[0], ", G ", out.dark_[1], ", B ",
                             out.dark_[2], ")");
  } else if (choice->method == RadiometryMethod::Stretch) {
    stretchRanges(input.stretch.value_or(Stretch{}), overview, out);
  } else {
    out.description = "8-bit sRGB colour as stored";
  }
  out.colourCalibration = calibrationOf(out, overview);
  return out;
}

}  // namespace vegstream::datasets
