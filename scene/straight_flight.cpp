#include "scene/straight_flight.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace vegstream::scene {

FlightPose poseAt(const StraightFlight& flight, double t, const geo::LocalFrame& frame, const GroundHeight& ground) {
  const double u = flight.durationS > 0.0 ? std::clamp(t / flight.durationS, 0.0, 1.0) : 0.0;
  const double lat = flight.start.latDeg + (flight.end.latDeg - flight.start.latDeg) * u;
  const double lon = flight.start.lonDeg + (flight.end.lonDeg - flight.start.lonDeg) * u;

  // Highest ground within ~300 m (0.003°) of the camera, so it clears nearby walls.
  double groundM = -1e9;
  for (double dLat : {-0.003, 0.0, 0.003})
    for (double dLon : {-0.003, 0.0, 0.003}) {
      const double h = ground(lat + dLat, lon + dLon);
      if (!std::isnan(h)) groundM = std::max(groundM, h);
    }
  if (groundM < -1e8) groundM = 0.0;

  FlightPose pose;
  pose.position = {lat, lon, groundM + flight.altitudeAboveTerrainM};
  const glm::dvec3 here = frame.toLocal(pose.position);
  const glm::dvec3 ahead = frame.toLocal({flight.end.latDeg, flight.end.lonDeg, pose.position.heightM});
  const glm::dvec3 startLocal = frame.toLocal({flight.start.latDeg, flight.start.lonDeg, pose.position.heightM});
  glm::dvec3 dir = ahead - startLocal;  // the flight direction, stable through the whole path
  const glm::dvec3 up = frame.upAt(pose.position);
  dir -= up * glm::dot(dir, up);
  dir = glm::normalize(dir);
  const double pitch = flight.pitchDeg * M_PI / 180.0;
  pose.camera.position = here;
  pose.camera.forward = glm::normalize(dir * std::cos(pitch) + up * std::sin(pitch));
  pose.camera.up = up;
  return pose;
}

}  // namespace vegstream::scene
