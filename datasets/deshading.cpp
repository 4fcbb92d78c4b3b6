// De-shading imagery with the DEM's normals and the acquisition sun (deshading.h).
// Lambert's cosine law; the direct/diffuse split of the topographic correction literature
// (P. M. Teillet, B. Guindon, D. G. Goodenough, "On the slope-aspect correction of
// multispectral scanner data", Canadian Journal of Remote Sensing 8(2), 84–106, 1982).

#include "datasets/deshading.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace vegstream::datasets {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// dh/d(axis) at index i of a line of n samples read by h(i): central where both neighbours
// are valid, one-sided where one is, 0 where neither is.
template <class H>
double slopeAlong(H&& h, int i, int n, double pixelM) {
  const float c = h(i);
  const float lo = i > 0 ? h(i - 1) : NAN, hi = i + 1 < n ? h(i + 1) : NAN;
  const bool l = std::isfinite(lo), r = std::isfinite(hi);
  if (l && r) return (hi - lo) / (2.0 * pixelM);
  if (r) return (hi - c) / pixelM;
  if (l) return (c - lo) / pixelM;
  return 0.0;
}

}  // namespace

glm::dvec3 sunVectorEnu(const SunAngles& sun) {
  const double az = sun.azimuthDeg * kDegToRad, el = sun.elevationDeg * kDegToRad;
  return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

double shading(const glm::dvec3& normal, const glm::dvec3& sun, double k) {
  return k * std::max(0.0, glm::dot(normal, sun)) + (1.0 - k);
}

float deshadingGain(const glm::dvec3& normal, const glm::dvec3& sun, double k) {
  const double flat = shading({0.0, 0.0, 1.0}, sun, k);
  const double gain = flat / shading(normal, sun, k);
  return std::clamp(static_cast<float>(gain), kMinDeshadingGain, kMaxDeshadingGain);
}

std::vector<glm::vec3> tileNormals(const std::vector<float>& heights, int size, double pixelM) {
  std::vector<glm::vec3> normals(heights.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  const auto at = [&](int i, int j) {
    return heights[static_cast<size_t>(j) * static_cast<size_t>(size) + static_cast<size_t>(i)];
  };
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      if (!std::isfinite(at(i, j))) continue;
      const double dhdx = slopeAlong([&](int c) { return at(c, j); }, i, size, pixelM);
      // Rows run from the north: north is towards smaller j.
      const double dhdy = -slopeAlong([&](int r) { return at(i, r); }, j, size, pixelM);
      normals[static_cast<size_t>(j) * static_cast<size_t>(size) + static_cast<size_t>(i)] =
          glm::vec3(glm::normalize(glm::dvec3(-dhdx, -dhdy, 1.0)));
    }
  }
  return normals;
}

}  // namespace vegstream::datasets
