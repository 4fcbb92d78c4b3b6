#pragma once
// Seed triangles: the terrain triangles plants grow on (seed 001_3eca9f2c7752e4fb.txt §2.1,
// §3.1). They are the bintree's triangles at one fixed level (the *seed level*, chosen from a
// target world-space area), so the same piece of ground is the same seed triangle — the same
// TriPath and the same vertices — whatever the camera and however ROAM tessellates around it;
// a ROAM leaf coarser than the seed level is refined on the fly by midpoint splits, without the
// heightmap (then the seed triangle is marked `interpolated`).
//
// Plant count per triangle, eq. 1: n = min(ρ · A_s, n_max), A_s the triangle's projected area
// in pixels², n_max when a vertex is behind the near plane. Eq. 2 (the cheap alternative):
// n' = min(ρ · A_w · |n̂ · v/‖v‖| / ‖v‖², n_max), v from the observer to the triangle's centre;
// here multiplied by (pixels per radian)² so that ρ means plants per pixel² in both rules
// (A_w cos / ‖v‖² is a solid angle; times px/rad squared it is the area on screen near the
// centre of the view).
//
// Two departures from the seed (issue 18), so that the same view grows the same plants at any
// window size and a close camera sees a real meadow:
//   - pixels are *reference* pixels, of a view kReferenceLinesPx tall with the same field of
//     view: ρ is a level of detail, not a property of the window;
//   - eq. 1 is only the level of detail (lodCount). What grows is capped by the ground instead:
//     N = min(lodCount, D · A_w) with D the densest species' plants per m²; each species then
//     stops at its own min(lodCount, D_s · A_w) (vegetation/plant_seeding.h speciesPlantCount).

#include <array>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "terrain/bintree.h"
#include "terrain/eye_space.h"

namespace vegstream::terrain {

enum class PlantCountRule { ScreenArea, WorldArea };  // eq. 1, eq. 2

// The viewport height that ρ's pixels are measured at (a 1080p view).
inline constexpr double kReferenceLinesPx = 1080.0;

struct SeedOptions {
  double targetAreaM2 = 24.0;     // world area of a seed triangle (the seed level is the nearest)
  double horizonM = 250.0;        // no seeds where the nearest vertex is farther (§3.1)
  double density = 0.1;           // ρ: plants per reference pixel² of projected area
  double maxPlants = 16384.0;     // n_max per seed triangle: a safety ceiling, not the density
  double groundDensityM2 = 150.0;  // D: the densest species' plants per m² (the caller's catalog)
  PlantCountRule rule = PlantCountRule::ScreenArea;
  // Belyaev's contour term (seed 004 §2.2): where the ground is seen edge-on the projected area
  // (∝ |n·r|) is replaced by (1 − t)|n·r| + t, t = (1 − |n·r|)^α, so grass stays dense on
  // contours and at grazing angles (contourFactor); 0: off, eq. 1 / 2 as the core seed has them.
  // Off by default (`--plant-contour`): at eye height in the Kolob meadow eq. 1 alone covers
  // 92 % of the ground 30–100 m away; Belyaev's α = 8 makes it 100 % with 4.8 × the plants.
  double contourAlpha = 0.0;
  bool refineToSeedLevel = true;  // ROAM reaches the seed level inside the horizon, so seed
                                  // triangles have sampled (not interpolated) vertices
};

struct SeedTriangle {
  TriPath path;                           // the identity of the ground it covers
  std::array<glm::dvec3, 3> world{};      // apex, left, right in the local ENU frame (m)
  std::array<glm::vec3, 3> fromCamera{};  // world − camera, for the GPU
  float plantCount = 0.0f;                // N = min(lodCount, D · areaM2) · horizon fade
  float lodCount = 0.0f;                  // eq. 1 or 2 (n_max when nearPlane)
  float areaM2 = 0.0f;                    // ground area (of the world vertices)
  float nearestM = 0.0f;                  // distance from the camera to the nearest vertex
  bool nearPlane = false;                 // a vertex behind the near plane: n_max
  bool interpolated = false;              // refined below a coarser leaf without the heightmap
  TriCorners corners{};                   // on the bintree grid
  int32_t piece = -1;                     // index into the PieceSet it lies in (−1: none)
  // Filled by StreamedTerrain: the imagery layer drawn under it and each vertex's uv there.
  int32_t imageryLayer = -1;
  std::array<glm::vec2, 3> imageryUv{};
  // While the imagery changes (a finer tile replaced a coarser one, or the first arrived): the
  // layer drawn before (−1: none) and the weight of the new one, 0 → 1. Plants cross-fade by
  // size between the species each picks (vegetation/plant_seeding.h).
  int32_t previousLayer = -1;
  std::array<glm::vec2, 3> previousUv{};
  float imageryBlend = 1.0f;
};

// The 64-bit identity of a seed triangle for plant hashing (vegetation/plant_seeding.h): a mix
// of its path, the same in every session and from every viewpoint.
uint64_t seedKey(const TriPath& path);

// Projected area (pixels², at the view's own resolution) of an eye-space triangle entirely in
// front of the near plane.
double screenAreaPx(const EyeView& view, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// Eq. 1 in reference pixels. Sets nearPlane when a vertex is behind the near plane (then n_max).
double plantCountScreen(const EyeView& view, const std::array<glm::dvec3, 3>& eye, const SeedOptions& o,
                        bool* nearPlane = nullptr);
// Eq. 2 from eye-space vertices (the observer is at the origin).
double plantCountWorld(const EyeView& view, const std::array<glm::dvec3, 3>& eye, const SeedOptions& o);

// Belyaev's contour term as a factor on eq. 1 / 2's count: ((1 − t) c + t) / c with c = |n·r|
// (the cosine between the ground's normal and the direction to the camera, floored at 1e-3) and
// t = (1 − c)^α; 1 with α = 0. At eye height (1.7 m) ground 30 m away (c ≈ 0.057) counts 11 ×.
double contourFactor(double cosine, double alpha);

// Area of a triangle of world (or eye) vertices, m².
double groundArea(const std::array<glm::dvec3, 3>& v);

// The count a seed triangle grows: min(lodCount, D · areaM2) · horizonFade(nearestM, horizonM).
double groundPlantCount(double lodCount, double areaM2, double nearestM, const SeedOptions& o);

// The factor on a seed triangle's plant count at distance `nearestM` (to its nearest vertex, as
// the horizon cut is measured): 1 within ¾ of the horizon, falling smoothly to 0 at it. Plants
// then leave at the end of their sequence, shrinking (vegetation/plant_seeding.h sequenceFade),
// instead of a triangle's 3–10 plants vanishing together at the cut (issue 18).
double horizonFade(double nearestM, double horizonM);

// The bintree level whose triangles' ground area at latitude `latDeg` is nearest `areaM2`.
int seedLevelFor(const BintreeGrid& grid, double latDeg, double areaM2);
// The bintree grid of a dataset with enough levels below its pixels for seed triangles of
// `areaM2` (at most kMaxExtraLevels more).
inline constexpr int kMaxExtraLevels = 8;
BintreeGrid gridForSeeds(int rootZoom, int maxZoom, double latDeg, double areaM2);
// Ground area of a triangle of `level` at latitude `latDeg`.
double triangleAreaM2(const BintreeGrid& grid, int level, double latDeg);

}  // namespace vegstream::terrain
