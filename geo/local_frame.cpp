#include "geo/local_frame.h"

#include <GeographicLib/LocalCartesian.hpp>

namespace vegstream::geo {

LocalFrame::LocalFrame(const Geodetic& origin)
    : origin_(origin),
      lc_(std::make_unique<GeographicLib::LocalCartesian>(origin.latDeg, origin.lonDeg, origin.heightM)) {}

LocalFrame::~LocalFrame() = default;
LocalFrame::LocalFrame(const LocalFrame& other)
    : origin_(other.origin_), lc_(std::make_unique<GeographicLib::LocalCartesian>(*other.lc_)) {}
LocalFrame& LocalFrame::operator=(const LocalFrame& other) {
  if (this != &other) {
    origin_ = other.origin_;
    lc_ = std::make_unique<GeographicLib::LocalCartesian>(*other.lc_);
  }
  return *this;
}
LocalFrame::LocalFrame(LocalFrame&&) noexcept = default;
LocalFrame& LocalFrame::operator=(LocalFrame&&) noexcept = default;

glm::dvec3 LocalFrame::toLocal(const Geodetic& p) const {
  glm::dvec3 enu;
  lc_->Forward(p.latDeg, p.lonDeg, p.heightM, enu.x, enu.y, enu.z);
  return enu;
}

Geodetic LocalFrame::toGeodetic(const glm::dvec3& enu) const {
  Geodetic p;
  lc_->Reverse(enu.x, enu.y, enu.z, p.latDeg, p.lonDeg, p.heightM);
  return p;
}

glm::dvec3 LocalFrame::upAt(const Geodetic& p) const { return upAt(p, toLocal(p)); }

glm::dvec3 LocalFrame::upAt(const Geodetic& p, const glm::dvec3& base) const {
  const glm::dvec3 above = toLocal(Geodetic{p.latDeg, p.lonDeg, p.heightM + 1.0});
  return above - base;  // exactly unit length: 1 m along the ellipsoid normal
}

LocalFrame frameAtCentre(const GeoBounds& extent, double heightM) {
  const glm::dvec2 c = extent.centre();
  return LocalFrame(Geodetic{c.y, c.x, heightM});
}

}  // namespace vegstream::geo
