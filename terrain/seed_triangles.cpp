// Seed-triangle plant counts (eq. 1, eq. 2) and the seed level; seed 001_3eca9f2c7752e4fb.txt
// §2.1 and §3.1; the contour term of seed 004_4f0be6bef8094cc2.txt (Belyaev) §2.2.

#include "terrain/seed_triangles.h"

#include "core/hash.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

namespace vegstream::terrain {
namespace {
constexpr double kEarthCircumferenceM = 40075016.685578488;
}

namespace {
// |n·r|: the triangle's unit normal against the unit direction from its centre to the camera
// (at the origin of eye space); 1 for a degenerate triangle.
double viewCosine(const std::array<glm::dvec3, 3>& eye) {
  const glm::dvec3 cross = glm::cross(eye[1] - eye[0], eye[2] - eye[0]);
  const glm::dvec3 centre = (eye[0] + eye[1] + eye[2]) / 3.0;
  const double l = glm::length(cross) * glm::length(centre);
  return l > 0.0 ? std::abs(glm::dot(cross, centre)) / l : 1.0;
}
}  // namespace

double screenAreaPx(const EyeView& view, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  auto project = [&](const glm::dvec3& p) { return glm::dvec2(p.x / -p.z, p.y / -p.z) * view.pixelsPerRadian; };
  const glm::dvec2 pa = project(a), pb = project(b), pc = project(c);
  return 0.5 * std::abs((pb.x - pa.x) * (pc.y - pa.y) - (pc.x - pa.x) * (pb.y - pa.y));
}

namespace {
// Reference pixels² per pixel² of this view.
double referenceScale(const EyeView& view) {
  assert(view.viewportHeightPx > 0.0);
  const double s = kReferenceLinesPx / view.viewportHeightPx;
  return s * s;
}
}  // namespace

double plantCountScreen(const EyeView& view, const std::array<glm::dvec3, 3>& eye, const SeedOptions& o,
                        bool* nearPlane) {
  const bool behind = std::any_of(eye.begin(), eye.end(), [&](const glm::dvec3& p) { return -p.z < view.nearM; });
  if (nearPlane) *nearPlane = behind;
  if (behind) return o.maxPlants;
  const double contour = o.contourAlpha > 0.0 ? contourFactor(viewCosine(eye), o.contourAlpha) : 1.0;
  return std::min(o.density * screenAreaPx(view, eye[0], eye[1], eye[2]) * referenceScale(view) * contour,
                  o.maxPlants);
}

double contourFactor(double cosine, double alpha) {
  if (alpha <= 0.0) return 1.0;
  const double c = std::clamp(std::abs(cosine), 1e-3, 1.0);
  const double t = std::pow(1.0 - c, alpha);
  return ((1.0 - t) * c + t) / c;
}

double groundArea(const std::array<glm::dvec3, 3>& v) {
  return 0.5 * glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
}

double groundPlantCount(double lodCount, double areaM2, double nearestM, const SeedOptions& o) {
  return std::min(lodCount, o.groundDensityM2 * areaM2) * horizonFade(nearestM, o.horizonM);
}

double horizonFade(double nearestM, double horizonM) {
  assert(horizonM > 0.0);
  const double t = std::clamp((nearestM - 0.75 * horizonM) / (0.25 * horizonM), 0.0, 1.0);
  return 1.0 - t * t * (3.0 - 2.0 * t);
}

double plantCountWorld(const EyeView& view, const std::array<glm::dvec3, 3>& eye, const SeedOptions& o) {
  const glm::dvec3 cross = glm::cross(eye[1] - eye[0], eye[2] - eye[0]);
  const double area = 0.5 * glm::length(cross);
  if (area <= 0.0) return 0.0;
  const glm::dvec3 n = cross / (2.0 * area);
  const glm::dvec3 v = (eye[0] + eye[1] + eye[2]) / 3.0;
  const double d2 = glm::dot(v, v);
  if (d2 <= 0.0) return o.maxPlants;
  const double cosine = std::abs(glm::dot(n, v)) / std::sqrt(d2);
  const double k = view.pixelsPerRadian;
  const double contour = o.contourAlpha > 0.0 ? contourFactor(cosine, o.contourAlpha) : 1.0;
  return std::min(o.density * area * cosine / d2 * k * k * referenceScale(view) * contour, o.maxPlants);
}

double triangleAreaM2(const BintreeGrid& grid, int level, double latDeg) {
  const double side = kEarthCircumferenceM / std::ldexp(1.0, grid.rootZoom()) * std::cos(latDeg * M_PI / 180.0);
  return side * side / std::ldexp(1.0, level + 1);  // a root square is two level-0 triangles
}

BintreeGrid gridForSeeds(int rootZoom, int maxZoom, double latDeg, double areaM2) {
  const int extra = std::min(kMaxExtraLevels, 31 - maxZoom - kTileLevels / 2);
  const BintreeGrid deepest(rootZoom, maxZoom, std::max(0, 2 * (extra / 2)));
  const int seedLevel = seedLevelFor(deepest, latDeg, areaM2);
  return BintreeGrid(rootZoom, maxZoom, std::max(0, seedLevel - deepest.pixelLevel()));
}

int seedLevelFor(const BintreeGrid& grid, double latDeg, double areaM2) {
  const double l = std::log2(triangleAreaM2(grid, 0, latDeg) / areaM2);
  return std::clamp(static_cast<int>(std::lround(l)), 0, grid.maxLevel());
}

uint64_t seedKey(const TriPath& path) {
  const uint32_t root =
      mix32(static_cast<uint32_t>(path.rootX) ^
            mix32(static_cast<uint32_t>(path.rootY) ^ mix32(path.tree | (uint32_t{path.level} << 8))));
  const uint32_t lo = mix32(root ^ static_cast<uint32_t>(path.bits));
  const uint32_t hi = mix32(lo ^ static_cast<uint32_t>(path.bits >> 32) ^ 0x9E3779B9u);
  return (uint64_t{hi} << 32) | lo;
}

}  // namespace vegstream::terrain
