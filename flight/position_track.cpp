#include "flight/position_track.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vegstream::flight {
namespace {

std::vector<double> column(const std::vector<TrackPoint>& points, double (*get)(const TrackPoint&)) {
  std::vector<double> out;
  out.reserve(points.size());
  for (const TrackPoint& p : points) out.push_back(get(p));
  return out;
}

}  // namespace

double groundOrZero(const GroundHeight& ground, double lat, double lon) {
  if (!ground) return 0.0;
  const double h = ground(lat, lon);
  return std::isfinite(h) ? h : 0.0;
}

PositionTrack::PositionTrack(const std::vector<TrackPoint>& points)
    : times_(column(points, [](const TrackPoint& p) { return p.t; })),
      frame_(geo::Geodetic{points.at(0).lat, points.at(0).lon, 0.0}),
      alt_(times_, column(points, [](const TrackPoint& p) { return p.altM; })),
      terrainWeight_(times_,
                     column(points, [](const TrackPoint& p) { return p.altRef == AltRef::Terrain ? 1.0 : 0.0; })) {
  // Points on the ellipsoid (height 0) in the frame: z carries the earth's curvature, so
  // converting back gives each keyframe's lat/lon exactly.
  std::vector<glm::dvec3> local;
  local.reserve(points.size());
  for (const TrackPoint& p : points) local.push_back(frame_.toLocal({p.lat, p.lon, 0.0}));
  if (points.size() == 1) {
    single_ = local[0];
    return;
  }
  curve_.emplace(std::move(local));
  knotOfTime_.emplace(times_, curve_->knots());
}

geo::Geodetic PositionTrack::horizontal(double t) const {
  t = std::clamp(t, times_.front(), times_.back());
  const glm::dvec3 p = curve_ ? curve_->position(knotOfTime_->value(t)) : single_;
  geo::Geodetic g = frame_.toGeodetic(p);
  g.heightM = 0.0;
  return g;
}

geo::Geodetic PositionTrack::position(double t, const GroundHeight& ground, double minClearanceM) const {
  t = std::clamp(t, times_.front(), times_.back());
  geo::Geodetic g = horizontal(t);
  const double under = groundOrZero(ground, g.latDeg, g.lonDeg);
  const double height = alt_.value(t) + terrainWeight_.value(t) * under;
  g.heightM = std::max(height, under + minClearanceM);
  return g;
}

}  // namespace vegstream::flight
