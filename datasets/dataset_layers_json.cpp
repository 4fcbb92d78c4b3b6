// dataset.json's layer objects ↔ DatasetMeta (dataset_layers_json.h; the format and why layers
// newer than format version 1 may be absent are in dataset_format.cpp): "imagery" with its
// radiometry and deshading record, "ndvi", "landcover" and "canopy".
#include "datasets/dataset_layers_json.h"

#include <array>
#include <string>

#include "core/printable.h"
#include "datasets/colour_calibration_json.h"
#include "datasets/message.h"

namespace vegstream::datasets::dataset_json {
namespace {

constexpr const char* kNdviEncoding = "ndvi8";
constexpr const char* kLandcoverEncoding = "class8";
constexpr const char* kCanopyEncoding = "decimetre16";

Result<DeshadingRecord> parseDeshading(const json& d, const FieldReader& f) {
  const std::string at = "imagery.radiometry.deshading";
  if (!d.is_object()) return f.bad(at, "must be an object");
  DeshadingRecord r;
  VEG_TRY_ASSIGN(r.source, f.text(d, "source", at + ".source"));
  if (r.source != "imagery datetime" && r.source != "given" && r.source != "estimated" && r.source != "none")
    return f.bad(at + ".source",
                 concat("is '", printable(r.source), "'; expected imagery datetime, given, estimated or none"));
  if (auto n = d.find("note"); n != d.end() && !n->is_null()) VEG_TRY_ASSIGN(r.note, f.text(d, "note", at + ".note"));
  if (r.source == "none") return r;
  VEG_TRY_ASSIGN(r.sunAzimuthDeg, f.number(d, "sun_azimuth_deg", at + ".sun_azimuth_deg", 0.0, 360.0));
  VEG_TRY_ASSIGN(r.sunElevationDeg, f.number(d, "sun_elevation_deg", at + ".sun_elevation_deg", -90.0, 90.0));
  VEG_TRY_ASSIGN(r.directFraction, f.number(d, "direct_fraction", at + ".direct_fraction", 0.0, 1.0));
  return r;
}

Result<RadiometryRecord> parseRadiometry(const json& r, const FieldReader& f) {
  const std::string at = "imagery.radiometry";
  if (!r.is_object()) return f.bad(at, "must be an object");
  RadiometryRecord m;
  VEG_TRY_ASSIGN(m.method, f.text(r, "method", at + ".method"));
  if (m.method != "reflectance" && m.method != "srgb" && m.method != "stretch")
    return f.bad(at + ".method", concat("is '", printable(m.method), "'; expected reflectance, srgb or stretch"));
  constexpr double kBig = 1e12;
  VEG_TRY_ASSIGN(m.scale, optionalNumber(r, "scale", at + ".scale", 0.0, kBig, f));
  VEG_TRY_ASSIGN(m.offset, optionalNumber(r, "offset", at + ".offset", -kBig, kBig, f));
  VEG_TRY_ASSIGN(m.darkObjectPercentile,
                 optionalNumber(r, "dark_object_percentile", at + ".dark_object_percentile", 0.0, 100.0, f));
  VEG_TRY_ASSIGN(m.darkObjectReflectance,
                 optionalNumber(r, "dark_object_reflectance", at + ".dark_object_reflectance", 0.0, 1.0, f));
  if (auto d = r.find("dark_object"); d != r.end() && !d->is_null()) {
    if (!d->is_array() || d->size() != 3) return f.bad(at + ".dark_object", "must be an array of 3 numbers");
    std::array<double, 3> v{};
    for (size_t i = 0; i < 3; ++i) {
      if (!(*d)[i].is_number()) return f.bad(at + ".dark_object", "must be an array of 3 numbers");
      v[i] = (*d)[i].get<double>();
    }
    m.darkObject = v;
  }
  if (auto d = r.find("deshading"); d != r.end() && !d->is_null()) VEG_TRY_ASSIGN(m.deshading, parseDeshading(*d, f));
  return m;
}

json radiometryJson(const RadiometryRecord& r) {
  json j = {{"method", r.method}};
  if (r.scale) j["scale"] = *r.scale;
  if (r.offset) j["offset"] = *r.offset;
  if (r.darkObject) j["dark_object"] = *r.darkObject;
  if (r.darkObjectPercentile) j["dark_object_percentile"] = *r.darkObjectPercentile;
  if (r.darkObjectReflectance) j["dark_object_reflectance"] = *r.darkObjectReflectance;
  if (r.deshading) {
    const DeshadingRecord& d = *r.deshading;
    json dj = {{"source", d.source}};
    if (d.source != "none") {
      dj["sun_azimuth_deg"] = d.sunAzimuthDeg;
      dj["sun_elevation_deg"] = d.sunElevationDeg;
      dj["direct_fraction"] = d.directFraction;
    }
    if (!d.note.empty()) dj["note"] = d.note;
    j["deshading"] = dj;
  }
  return j;
}

}  // namespace

const char* imageryExtension(ImageryFormat f) { return f == ImageryFormat::Jpeg ? "jpg" : "png"; }

Status parseImagery(const json& im, const FieldReader& f, DatasetMeta& m) {
  int64_t count = 0;
  if (!im.is_object()) return f.bad("imagery", "must be an object or null");
  std::string fmt;
  VEG_TRY_ASSIGN(fmt, f.text(im, "format", "imagery.format"));
  if (fmt == "jpeg")
    m.imagery = ImageryFormat::Jpeg;
  else if (fmt == "png")
    m.imagery = ImageryFormat::Png;
  else
    return f.bad("imagery.format", concat("is '", printable(fmt), "'; expected jpeg or png"));
  VEG_TRY_ASSIGN(count, f.integer(im, "tile_count", "imagery.tile_count", 0, INT64_MAX));
  m.imageryTiles = static_cast<uint64_t>(count);
  if (auto dt = im.find("datetime"); dt != im.end() && !dt->is_null())
    VEG_TRY_ASSIGN(m.imageryDatetime, f.text(im, "datetime", "imagery.datetime"));
  if (auto r = im.find("radiometry"); r != im.end() && !r->is_null())
    VEG_TRY_ASSIGN(m.radiometry, parseRadiometry(*r, f));
  if (auto c = im.find("colour_calibration"); c != im.end() && !c->is_null())
    VEG_TRY_ASSIGN(m.colourCalibration, parseColourCalibration(*c, f.source()));
  return {};
}

Status parseNdvi(const json& nd, const FieldReader& f, DatasetMeta& m) {
  int64_t count = 0;
  if (!nd.is_object()) return f.bad("ndvi", "must be an object or null");
  std::string ndviEnc;
  VEG_TRY_ASSIGN(ndviEnc, f.text(nd, "encoding", "ndvi.encoding"));
  if (ndviEnc != kNdviEncoding)
    return f.bad("ndvi.encoding", concat("is '", printable(ndviEnc), "'; expected ", kNdviEncoding));
  VEG_TRY_ASSIGN(count, f.integer(nd, "tile_count", "ndvi.tile_count", 0, INT64_MAX));
  m.ndvi = true;
  m.ndviTiles = static_cast<uint64_t>(count);
  return {};
}

// dataset.json's "landcover" object (not null) into m.landcover / m.landcoverTiles.
Status parseLandcover(const json& lc, const FieldReader& f, DatasetMeta& m) {
  if (!lc.is_object()) return f.bad("landcover", "must be an object or null");
  std::string encoding, scheme;
  int64_t count = 0;
  VEG_TRY_ASSIGN(encoding, f.text(lc, "encoding", "landcover.encoding"));
  if (encoding != kLandcoverEncoding)
    return f.bad("landcover.encoding", concat("is '", printable(encoding), "'; expected ", kLandcoverEncoding));
  VEG_TRY_ASSIGN(scheme, f.text(lc, "scheme", "landcover.scheme"));
  auto parsed = parseLandcoverScheme(scheme);
  if (!parsed || !*parsed)
    return f.bad("landcover.scheme", concat("is '", printable(scheme), "'; expected worldcover or nlcd"));
  VEG_TRY_ASSIGN(count, f.integer(lc, "tile_count", "landcover.tile_count", 0, INT64_MAX));
  m.landcover = **parsed;
  m.landcoverTiles = static_cast<uint64_t>(count);
  return {};
}

// dataset.json's "canopy" object (not null) into m.canopyZoom / m.canopyTiles (issue 41 item 3).
Status parseCanopy(const json& c, const FieldReader& f, DatasetMeta& m) {
  if (!c.is_object()) return f.bad("canopy", "must be an object or null");
  std::string encoding;
  int64_t zoom = 0, count = 0;
  VEG_TRY_ASSIGN(encoding, f.text(c, "encoding", "canopy.encoding"));
  if (encoding != kCanopyEncoding)
    return f.bad("canopy.encoding", concat("is '", printable(encoding), "'; expected ", kCanopyEncoding));
  VEG_TRY_ASSIGN(zoom, f.integer(c, "zoom", "canopy.zoom", 0, 24));
  VEG_TRY_ASSIGN(count, f.integer(c, "tile_count", "canopy.tile_count", 0, INT64_MAX));
  m.canopyZoom = static_cast<int>(zoom);
  m.canopyTiles = static_cast<uint64_t>(count);
  return {};
}

json imageryJson(const DatasetMeta& m) {
  json imagery = nullptr;
  if (m.imagery) {
    imagery = {{"format", toString(*m.imagery)},
               {"tiles", concat("imagery/{z}/{x}/{y}.", imageryExtension(*m.imagery))},
               {"tile_count", m.imageryTiles}};
    if (!m.imageryDatetime.empty()) imagery["datetime"] = m.imageryDatetime;
    if (m.radiometry) imagery["radiometry"] = radiometryJson(*m.radiometry);
    if (m.colourCalibration) imagery["colour_calibration"] = colourCalibrationJson(*m.colourCalibration);
  }
  return imagery;
}

json ndviJson(const DatasetMeta& m) {
  if (!m.ndvi) return nullptr;
  return {{"encoding", kNdviEncoding}, {"tiles", "ndvi/{z}/{x}/{y}.png"}, {"tile_count", m.ndviTiles}};
}

json landcoverJson(const DatasetMeta& m) {
  if (!m.landcover) return nullptr;
  return {{"encoding", kLandcoverEncoding},
          {"scheme", toString(*m.landcover)},
          {"tiles", "landcover/{z}/{x}/{y}.png"},
          {"tile_count", m.landcoverTiles}};
}

json canopyJson(const DatasetMeta& m) {
  if (!m.canopyZoom) return nullptr;
  return {{"encoding", kCanopyEncoding},
          {"zoom", *m.canopyZoom},
          {"tiles", "canopy/{z}/{x}/{y}.png"},
          {"tile_count", m.canopyTiles}};
}

}  // namespace vegstream::datasets::dataset_json
