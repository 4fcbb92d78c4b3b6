#pragma once
// A local East-North-Up frame anchored at one geodetic point (GeographicLib's LocalCartesian:
// exact WGS 84 geocentric → ENU, so earth curvature is included: a point 20 km away sits about
// 31 m below the tangent plane). Everything the renderer draws lives in this frame, in double
// precision on the CPU; only camera-relative offsets are handed to the GPU as float.

#include <memory>

#include <glm/vec3.hpp>

#include "geo/bounds.h"
#include "geo/geodetic.h"

namespace GeographicLib {
class LocalCartesian;
}

namespace vegstream::geo {

class LocalFrame {
 public:
  explicit LocalFrame(const Geodetic& origin);
  ~LocalFrame();
  LocalFrame(const LocalFrame& other);
  LocalFrame& operator=(const LocalFrame& other);
  LocalFrame(LocalFrame&&) noexcept;
  LocalFrame& operator=(LocalFrame&&) noexcept;

  const Geodetic& origin() const { return origin_; }

  // x = east, y = north, z = up, metres.
  glm::dvec3 toLocal(const Geodetic& p) const;
  Geodetic toGeodetic(const glm::dvec3& enu) const;

  // The local "up" (ellipsoid normal) at p, expressed in this frame: it tilts away from +z
  // by about 1 mrad per 6.4 km of distance from the origin.
  glm::dvec3 upAt(const Geodetic& p) const;
  // The same, given base = toLocal(p) (one projection fewer; the result is bit-identical).
  glm::dvec3 upAt(const Geodetic& p, const glm::dvec3& base) const;

 private:
  Geodetic origin_;
  std::unique_ptr<GeographicLib::LocalCartesian> lc_;
};

// The frame a dataset is drawn in: anchored at the centre of its lon/lat extent (the middle of
// the longitude span, across the antimeridian too) at `heightM`, typically the middle of the
// dataset's height range so that |z| stays small over the whole area.
LocalFrame frameAtCentre(const GeoBounds& extent, double heightM);

}  // namespace vegstream::geo
