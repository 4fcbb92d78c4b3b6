// CRSs through OGRSpatialReference (crs.h): what PROJ knows, named and compared by PROJ.

#include "geo/crs.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cctype>

#include <GeographicLib/UTMUPS.hpp>
#include <ogr_spatialref.h>

#include "geo/gdal_quiet.h"

namespace vegstream::geo {

struct Crs::Data {
  std::string wkt, projjson, name, code;
  std::optional<int> epsg;
  bool geographic = false, wgs84LonLat = false, webMercator = false;
  uint64_t id = 0;
};

namespace {

std::atomic<uint64_t> nextId{1};

std::string_view trim(std::string_view s) {
  const auto blank = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

bool allDigits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

std::string shortText(std::string_view text) {
  std::string t(text.substr(0, 60));
  for (char& c : t)
    if (c == '\n' || c == '\r') c = ' ';
  return text.size() > 60 ? t + "…" : t;
}

std::string exportString(OGRSpatialReference& srs, bool json) {
  char* out = nullptr;
  const char* const wktOptions[] = {"FORMAT=WKT2_2019", nullptr};
  const OGRErr e = json ? srs.exportToPROJJSON(&out, nullptr) : srs.exportToWkt(&out, wktOptions);
  std::string s = (e == OGRERR_NONE && out) ? out : "";
  CPLFree(out);
  return s;
}

// Everything a Crs keeps, from a parsed OGRSpatialReference.
std::shared_ptr<Crs::Data> describe(OGRSpatialReference& srs) {
  auto d = std::make_shared<Crs::Data>();
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (srs.GetAuthorityName(nullptr) == nullptr) srs.AutoIdentifyEPSG();
  const char* auth = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (auth && code && std::string(auth) == "EPSG" && allDigits(code)) d->epsg = std::stoi(code);
  d->code = d->epsg ? "EPSG:" + std::to_string(*d->epsg) : std::string();
  const char* name = srs.GetName();
  d->name = name ? name : "unnamed CRS";
  if (!d->code.empty()) d->name += " (" + d->code + ")";
  d->wkt = exportString(srs, false);
  d->projjson = exportString(srs, true);
  d->geographic = srs.IsGeographic() != 0;
  d->wgs84LonLat = d->epsg == 4326;
  d->webMercator = d->epsg == 3857;
  d->id = nextId.fetch_add(1);
  return d;
}

Result<std::shared_ptr<Crs::Data>> parse(std::string_view text, bool wkt) {
  GdalQuiet quiet;
  OGRSpatialReference srs;
  std::string t(trim(text));
  if (allDigits(t)) t = "EPSG:" + t;
  const OGRErr e = wkt ? srs.importFromWkt(t.c_str()) : srs.SetFromUserInput(t.c_str());
  if (e != OGRERR_NONE || srs.IsEmpty())
    return makeError(ErrorKind::InvalidInput,
                     "CRS '" + shortText(text) + "' is not one PROJ knows (" +
                         gdalReason(quiet, "expected EPSG:N, WKT, PROJJSON or a PROJ string") + ")");
  if (!srs.IsGeographic() && !srs.IsProjected() && !srs.IsCompound())
    return makeError(ErrorKind::InvalidInput,
                     "CRS '" + shortText(text) + "' is neither geographic nor projected; a raster needs one");
  if (srs.IsCompound()) srs.StripVertical();  // heights are the raster's values; their unit is read there
  return describe(srs);
}

}  // namespace

Crs::Crs() : d_(wgs84Crs().d_) {}

Result<Crs> Crs::fromUserInput(std::string_view text) {
  auto d = parse(text, false);
  if (!d) return d.error();
  return Crs(std::move(*d));
}

Result<Crs> Crs::fromWkt(const std::string& wkt) {
  auto d = parse(wkt, true);
  if (!d) return d.error();
  return Crs(std::move(*d));
}

std::string Crs::name() const { return d_->name; }
std::string Crs::code() const { return d_->code; }
std::optional<int> Crs::epsg() const { return d_->epsg; }
const std::string& Crs::projjson() const { return d_->projjson; }
const std::string& Crs::wkt() const { return d_->wkt; }
bool Crs::isGeographic() const { return d_->geographic; }
bool Crs::isWgs84LonLat() const { return d_->wgs84LonLat; }
bool Crs::isWebMercator() const { return d_->webMercator; }
uint64_t Crs::id() const { return d_->id; }

bool Crs::operator==(const Crs& other) const {
  if (d_ == other.d_) return true;
  if (d_->epsg && other.d_->epsg) return *d_->epsg == *other.d_->epsg;
  GdalQuiet quiet;
  OGRSpatialReference a, b;
  if (a.importFromWkt(d_->wkt.c_str()) != OGRERR_NONE || b.importFromWkt(other.d_->wkt.c_str()) != OGRERR_NONE)
    return false;
  return a.IsSame(&b) != 0;
}

namespace {
Crs fromCode(int epsg) {
  auto c = Crs::fromUserInput("EPSG:" + std::to_string(epsg));
  assert(c.ok());
  return *c;
}
}  // namespace

Crs wgs84Crs() {
  static const Crs crs = fromCode(4326);
  return crs;
}

Crs webMercatorCrs() {
  static const Crs crs = fromCode(3857);
  return crs;
}

Crs utmCrs(int zone, bool north) {
  assert(zone >= 1 && zone <= 60);
  return fromCode((north ? 32600 : 32700) + zone);
}

int standardUtmZone(double latDeg, double lonDeg) {
  assert(latDeg >= -90.0 && latDeg <= 90.0);
  // GeographicLib answers 0 (UPS) beyond 80°S / 84°N; a UTM zone is still wanted there, so
  // the latitude is clamped into the UTM band, which keeps the Svalbard exception at 84°N.
  const double lat = std::clamp(latDeg, -80.0, 83.999999);
  return GeographicLib::UTMUPS::StandardZone(lat, lonDeg);
}

}  // namespace vegstream::geo
