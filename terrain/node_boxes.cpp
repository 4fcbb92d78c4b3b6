// A selection node's geometry (node_boxes.h, tile_selection.h): its quad size and geometric
// error (Ulrich 2002, the chunk's error halving per level) and its conservative ENU box, with
// the memo that keeps the boxes from frame to frame.

#include "terrain/node_boxes.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "terrain/tile_selection.h"

namespace vegstream::terrain {
namespace {

// Mean earth radius; only used to size a few-millimetre-to-metres safety pad.
constexpr double kEarthRadiusM = 6'371'000.0;

// Latitude (degrees) of the node's edge nearest the equator (0 when it straddles it).
double latNearestEquator(const geo::TileId& t) {
  const geo::GeoBounds g = geo::tileBoundsLonLat(t);
  if (g.southDeg <= 0.0 && g.northDeg >= 0.0) return 0.0;
  return std::abs(g.southDeg) < std::abs(g.northDeg) ? g.southDeg : g.northDeg;
}

}  // namespace

double nodeQuadSizeM(const geo::TileId& node) {
  assert(geo::isValid(node));
  return geo::groundResolution(latNearestEquator(node), node.z, kNodeQuads);
}

double nodeGeometricErrorM(const geo::TileId& node) { return kErrorPerQuad * nodeQuadSizeM(node); }

// The corners, edge midpoints and centre at both heights, through the exact geodetic → ENU map
// (so the curvature drop of distant nodes is in it), padded by what a curved surface can bulge
// between those points: the sagitta c²/8R of the diagonal c between neighbouring samples, plus as
// much again times tan φ for the curvature of the parallels seen in the tangent plane.
NodeBox nodeBox(const geo::TileId& t, double hMin, double hMax, const geo::LocalFrame& frame) {
  NodeBox b{glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest()), 0.0};
  for (int fy = 0; fy <= 2; ++fy) {
    for (int fx = 0; fx <= 2; ++fx) {
      const glm::dvec2 lonLat = geo::tileXYToLonLat({t.x + 0.5 * fx, t.y + 0.5 * fy}, t.z);
      for (const double h : {hMin, hMax}) {
        const glm::dvec3 p = frame.toLocal({lonLat.y, lonLat.x, h});
        b.lo = glm::min(b.lo, p);
        b.hi = glm::max(b.hi, p);
      }
    }
  }
  const double quadM = nodeQuadSizeM(t);
  const double halfSide = 0.5 * kNodeQuads * quadM;
  const double c2 = 2.0 * halfSide * halfSide;
  const double lat = std::min(std::abs(latNearestEquator(t)), 85.0) * std::numbers::pi / 180.0;
  const double pad = c2 * (1.0 + std::tan(lat)) / (8.0 * kEarthRadiusM);
  b.lo -= glm::dvec3(pad);
  b.hi += glm::dvec3(pad);
  b.errorM = kErrorPerQuad * quadM;
  return b;
}

const NodeBox& NodeBoxes::at(const geo::TileId& t, double hMin, double hMax, const geo::LocalFrame& frame) {
  assert(boxes_.empty() || (origin_.latDeg == frame.origin().latDeg && origin_.lonDeg == frame.origin().lonDeg &&
                            origin_.heightM == frame.origin().heightM));
  origin_ = frame.origin();
  if (const auto it = boxes_.find(t); it != boxes_.end() && it->second.hMin == hMin && it->second.hMax == hMax) {
    ++hits_;
    return it->second.box;
  }
  ++misses_;
  if (boxes_.size() >= capacity_) boxes_.clear();
  Entry& e = boxes_[t];
  e = {hMin, hMax, nodeBox(t, hMin, hMax, frame)};
  return e.box;
}

}  // namespace vegstream::terrain
