// The acquisition sun of an import's imagery: stated, from its datetime, or estimated
// (deshading_plan.h).

#include "datasets/deshading_plan.h"

#include "datasets/message.h"
#include "geo/datetime.h"
#include "geo/solar_position.h"

namespace vegstream::datasets {
namespace {

DeshadingPlan none(std::string why) {
  DeshadingPlan p;
  p.record.source = "none";
  p.record.note = std::move(why);
  return p;
}

DeshadingPlan fromSun(const SunAngles& sun, const char* source, double k, std::string note) {
  if (sun.elevationDeg <= 0.0)
    return none(concat("the sun was ", sun.elevationDeg, " degrees below the horizon: not de-shaded"));
  DeshadingPlan p;
  p.sun = sunVectorEnu(sun);
  p.record.source = source;
  p.record.sunAzimuthDeg = sun.azimuthDeg;
  p.record.sunElevationDeg = sun.elevationDeg;
  p.record.directFraction = k;
  p.record.note = std::move(note);
  return p;
}

}  // namespace

Result<int64_t> imageryUnixMs(const std::string& iso) {
  auto t = geo::parseIsoDateTime(iso);
  if (!t) return makeError(ErrorKind::InvalidInput, concat("--imagery-datetime: ", t.error().message));
  return t->unixMs;
}

Result<DeshadingPlan> planDeshading(const GeoTiffImportOptions& o, const RadiometryRecord& radiometry,
                                    const ImageryTiling& tiling, const std::vector<geo::TileId>& tiles,
                                    glm::dvec2 centre,
                                    const std::function<std::vector<float>(const geo::TileId&)>& heightsOf,
                                    const std::function<std::optional<TileImagery>(const geo::TileId&)>& imageryOf,
                                    const Logger& log) {
  if (radiometry.method == "stretch") return none("display-stretched imagery is not linear light: not de-shaded");
  if (!o.deshade) return none("--deshading off");
  const double k = o.directFraction;
  if (o.imagerySun) return fromSun(*o.imagerySun, "given", k, "--imagery-sun");
  if (!o.imageryDatetime.empty()) {
    auto ms = imageryUnixMs(o.imageryDatetime);
    if (!ms) return ms.error();
    const geo::SolarPosition s = geo::solarPosition(*ms, centre.y, centre.x);
    return fromSun(
        {s.azimuthDeg, s.elevationDeg}, "imagery datetime", k,
        concat("NOAA solar position at the dataset's centre (", centre.y, ", ", centre.x, ") at ", o.imageryDatetime));
  }
  const SunEstimate e = estimateSun(collectShadingSamples(tiling, tiles, kTileSize, heightsOf, imageryOf), k);
  if (!e.found) {
    log->info("imagery: {}", e.note);
    return none(e.note);
  }
  log->info("imagery: the sun estimated at azimuth {:.1f}, elevation {:.1f} degrees ({})", e.sun.azimuthDeg,
            e.sun.elevationDeg, e.note);
  return fromSun(e.sun, "estimated", k, e.note);
}

}  // namespace vegstream::datasets
