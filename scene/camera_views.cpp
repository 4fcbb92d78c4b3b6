#include "scene/camera_views.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace vegstream::scene {

geo::Camera cameraFor(const geo::LocalFrame& frame, const FlightSample& sample) {
  geo::Camera c;
  const glm::dvec3 position = frame.toLocal(sample.position);
  const glm::dvec3 up = frame.upAt(sample.position);
  const glm::dvec3 northAhead =
      frame.toLocal({sample.position.latDeg + 1e-4, sample.position.lonDeg, sample.position.heightM});
  glm::dvec3 north = northAhead - position;
  north = glm::normalize(north - up * glm::dot(north, up));
  const glm::dvec3 east = glm::cross(north, up);
  const glm::dvec3 f = flight::forwardVector(sample.headingDeg, sample.pitchDeg);  // in east/north/up terms
  c.position = position;
  c.forward = glm::normalize(east * f.x + north * f.y + up * f.z);
  c.up = up;
  return c;
}

terrain::SelectionView selectionViewFor(const geo::Camera& camera, double widthPx, double heightPx) {
  terrain::SelectionView v;
  v.cameraEnu = camera.position;
  v.viewProjection = geo::projection(camera, widthPx / heightPx) * geo::viewRotation(camera) *
                     glm::translate(glm::dmat4(1.0), -camera.position);
  v.viewportHeightPx = heightPx;
  v.verticalFovRad = glm::radians(camera.verticalFovDeg);
  return v;
}

terrain::EyeView eyeViewFor(const geo::Camera& camera, double widthPx, double heightPx) {
  return terrain::EyeView::lookAlong(camera.position, camera.forward, camera.up, glm::radians(camera.verticalFovDeg),
                                     widthPx, heightPx, camera.nearM);
}

}  // namespace vegstream::scene
