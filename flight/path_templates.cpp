#include "flight/path_templates.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "flight/position_track.h"
#include "geo/local_frame.h"

namespace vegstream::flight {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// The extent as a metric box around its centre: the frame, half sizes and the long axis.
struct Area {
  geo::LocalFrame frame;
  double halfEastM;
  double halfNorthM;
  bool northSouth;  // the longer axis runs north–south

  explicit Area(const geo::GeoBounds& b) : frame(geo::Geodetic{b.centre().y, b.centre().x, 0.0}) {
    const double lat = b.centre().y;
    halfEastM = 0.5 * (frame.toLocal({lat, b.eastDeg, 0.0}).x - frame.toLocal({lat, b.westDeg, 0.0}).x);
    if (b.crossesAntimeridian()) halfEastM = std::abs(halfEastM);
    const double lon = b.centre().x;
    halfNorthM = 0.5 * (frame.toLocal({b.northDeg, lon, 0.0}).y - frame.toLocal({b.southDeg, lon, 0.0}).y);
    northSouth = halfNorthM >= halfEastM;
  }
  double halfLong() const { return northSouth ? halfNorthM : halfEastM; }
  double halfShort() const { return northSouth ? halfEastM : halfNorthM; }
  // along = metres on the long axis (north or east), across = on the short axis (east or north).
  geo::Geodetic at(double along, double across) const {
    const glm::dvec3 p = northSouth ? glm::dvec3(across, along, 0.0) : glm::dvec3(along, across, 0.0);
    return frame.toGeodetic(p);
  }
  double axisHeading() const { return northSouth ? 0.0 : 90.0; }
};

Keyframe key(double t, const geo::Geodetic& g, double altM, AltRef ref, double heading, double pitch) {
  return Keyframe{t, g.latDeg, g.lonDeg, altM, ref, heading, pitch};
}

FlightPath benchmark(const Area& a) {
  struct Row {
    double t, along, altM, pitch;
  };
  // Seed 001 §4: high at the start, near the ground at 10 s, climbing after 20 s.
  static constexpr Row kRows[] = {{0, -3400, 1800, -40}, {5, -1500, 600, -25}, {10, -200, 15, -8},   {15, 0, 15, -5},
                                  {20, 200, 15, -8},     {25, 1500, 600, -20}, {30, 3400, 1800, -35}};
  const double scale = std::min(1.0, 0.8 * a.halfLong() / 3400.0);
  FlightPath p;
  p.name = "benchmark-30s";
  p.description = "Seed 001 §4 benchmark: 1800 m above the terrain at 0 s, 15 m from 10 s to 20 s, 1800 m at 30 s.";
  for (const Row& r : kRows)
    p.keyframes.push_back(key(r.t, a.at(r.along * scale, 0.0), r.altM, AltRef::Terrain, a.axisHeading(), r.pitch));
  return p;
}

FlightPath canyonRun(const Area& a) {
  constexpr int kKeys = 13;
  constexpr double kSpeed = 150.0, kAltM = 60.0;
  const double along0 = -0.8 * a.halfLong(), along1 = 0.8 * a.halfLong();
  const double sway = 0.3 * a.halfShort();
  std::vector<glm::dvec2> pts;  // (along, across)
  for (int i = 0; i < kKeys; ++i) {
    const double u = static_cast<double>(i) / (kKeys - 1);
    pts.push_back({along0 + (along1 - along0) * u, sway * std::sin(u * 3.0 * M_PI)});
  }
  FlightPath p;
  p.name = "canyon-run";
  p.description = "Fast (150 m/s), low (60 m above the terrain) S-curve run along the dataset's long axis.";
  double t = 0.0;
  for (int i = 0; i < kKeys; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (i > 0) t += glm::length(pts[k] - pts[k - 1]) / kSpeed;
    const glm::dvec2 d = pts[std::min<std::size_t>(k + 1, kKeys - 1)] - pts[k > 0 ? k - 1 : 0];
    const glm::dvec2 en = a.northSouth ? glm::dvec2(d.y, d.x) : d;  // (east, north)
    const double heading = std::fmod(std::atan2(en.x, en.y) * kRadToDeg + 360.0, 360.0);
    p.keyframes.push_back(
        key(std::round(t * 1000.0) / 1000.0, a.at(pts[k].x, pts[k].y), kAltM, AltRef::Terrain, heading, -8.0));
  }
  return p;
}

FlightPath orbit(const Area& a, const GroundHeight& ground) {
  constexpr int kSteps = 24;  // keyframes every 15°, plus the closing one
  constexpr double kPeriodS = 120.0, kAboveM = 400.0;
  const double radius = std::min(1500.0, 0.5 * a.halfShort());
  const geo::Geodetic centre = a.frame.toGeodetic({0.0, 0.0, 0.0});
  double highest = -INFINITY;
  for (int i = 0; i < 72; ++i) {
    const double th = i * 5.0 / kRadToDeg;
    const geo::Geodetic g = a.frame.toGeodetic({radius * std::sin(th), radius * std::cos(th), 0.0});
    const double h = ground ? ground(g.latDeg, g.lonDeg) : NAN;
    if (std::isfinite(h)) highest = std::max(highest, h);
  }
  const bool known = std::isfinite(highest);
  const double centreGround = groundOrZero(ground, centre.latDeg, centre.lonDeg);
  const double altM = known ? highest + kAboveM : kAboveM;
  const double drop = known ? altM - centreGround : kAboveM;
  const double pitch = -std::atan2(drop, radius) * kRadToDeg;
  FlightPath p;
  p.name = "orbit";
  p.description = "A slow circle (120 s) around one point, looking at it.";
  for (int i = 0; i <= kSteps; ++i) {
    const double deg = 360.0 * i / kSteps;
    const double th = deg / kRadToDeg;
    const geo::Geodetic g = a.frame.toGeodetic({radius * std::sin(th), radius * std::cos(th), 0.0});
    p.keyframes.push_back(key(kPeriodS * i / kSteps, g, altM, known ? AltRef::Msl : AltRef::Terrain,
                              std::fmod(deg + 180.0, 360.0), pitch));
  }
  return p;
}

}  // namespace

const std::vector<std::string>& templateNames() {
  static const std::vector<std::string> kNames = {"benchmark-30s", "canyon-run", "orbit"};
  return kNames;
}

Result<FlightPath> makePathFromTemplate(const std::string& templateName, const geo::GeoBounds& datasetBounds,
                                        const GroundHeight& ground) {
  if (!(datasetBounds.heightDeg() > 0.0) || !(datasetBounds.widthDeg() > 0.0))
    return makeError(ErrorKind::InvalidInput, "cannot place a flight template over an empty dataset extent");
  const Area area(datasetBounds);
  FlightPath p;
  if (templateName == "benchmark-30s")
    p = benchmark(area);
  else if (templateName == "canyon-run")
    p = canyonRun(area);
  else if (templateName == "orbit")
    p = orbit(area, ground);
  else {
    std::string list;
    for (const std::string& n : templateNames()) list += (list.empty() ? "" : ", ") + n;
    return makeError(ErrorKind::InvalidInput, "unknown flight template \"" + templateName + "\"; known: " + list);
  }
  if (Status s = validateFlightPath(p, "template " + templateName); !s) return s.error();
  if (Status s = checkInside(p, datasetBounds); !s) return s.error();
  return p;
}

}  // namespace vegstream::flight
