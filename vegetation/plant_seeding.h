#pragma once
// The plants of one seed triangle: the CPU reference of the GPU classify pass
// (render/classify_pass.h, shaders/classify.comp) and of the species pipelines' placement.
// Core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2 (Philox per triangle and plant),
// §3.3 (species from the base colour, eq. 16–18), §3.4 (clusters, eq. 19–25); the density fade
// of seed 004_4f0be6bef8094cc2.txt §2.2.
//
// A triangle's plants form one fixed sequence, whatever the camera:
//   - cluster 0 is the "unclustered" part: its C seeds are spread over the whole triangle
//     (level 1) and each takes its own species at its own root — so a triangle with fewer than
//     C plants is seeded exactly as without clustering (§3.4);
//   - clusters 1, 2, … follow the hierarchical strata (stratified_clusters.h); each samples the
//     base colour once, at its centre, and all its C seeds get that species.
// A plant count N (eq. 1 or 2, a real number) shows the first min(N, C) seeds of cluster 0 and
// then (N − C) / C further clusters. The element at the fractional end is drawn scaled by the
// fraction (fade = clamp(count − index, 0, 1)), so as N grows with the camera's approach plants
// grow in at the end of the sequence and nothing moves or pops (seed 004 §2.2's fade by weight,
// here by size).
//
// Randomness: Philox-2×32-3 (vegetation/philox.h) with key = the low word of the triangle's
// 64-bit identity, counter = (cluster << 8 | slot, high word). Slots below.

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "vegetation/canopy_cells.h"
#include "vegetation/species_catalog.h"
#include "vegetation/stratified_clusters.h"

namespace vegstream::vegetation {

inline constexpr uint32_t kMaxClusterSize = 32;
inline constexpr uint32_t kMaxClustersPerTriangle = 1u << 24;  // the counter's cluster field

// Philox counter slots of a cluster (ctr0 = cluster << 8 | slot); s is the seed in the cluster.
namespace philox_slot {
inline constexpr uint32_t kCentre = 0;             // (u, v) of the cluster centre in its stratum
inline constexpr uint32_t kSpecies = 1;            // x: the cluster's species z
inline constexpr uint32_t kPosition = 2;           // + s: (u, v) of seed s in the stratum
inline constexpr uint32_t kHeightStiffness = 64;   // + s
inline constexpr uint32_t kOrientationWidth = 96;  // + s
inline constexpr uint32_t kColourSpecies = 128;    // + s: x colour modulation, y z of a cluster-0 seed
inline constexpr uint32_t kCanopy = 160;           // + s: x whether the group survives under a crown (canopy_cells.h)
inline constexpr uint32_t kLevelOffset = 255;      // with cluster field = level: the level's stratum offset
}  // namespace philox_slot
static_assert(philox_slot::kPosition + kMaxClusterSize <= philox_slot::kHeightStiffness);
static_assert(philox_slot::kColourSpecies + kMaxClusterSize <= philox_slot::kCanopy);
static_assert(philox_slot::kCanopy + kMaxClusterSize <= philox_slot::kLevelOffset);

struct SeedingOptions {
  uint32_t clusterSize = 8;  // C, 1 … kMaxClusterSize
  // Per species, the overflow thinning's pressure (overflow_thinning.h): 0 keeps every group.
  std::array<float, kMaxSpecies> thinning{};
  // The crowns near the camera (canopy_cells.h): groups under them thin out. Null: none.
  const CanopyTable* canopy = nullptr;
};

// One seed triangle as the seeding sees it (terrain/seed_triangles.h makes them).
struct SeedTriangleInput {
  uint64_t key = 0;                      // identity of the ground (a hash of its bintree path)
  std::array<glm::dvec3, 3> vertices{};  // apex, left, right (local ENU, m)
  float plantCount = 0.0f;               // N: how far the sequence goes, all species together
  // The level of detail (eq. 1 or 2; +∞: full detail) and the distance to the camera's nearest
  // vertex (0: at the camera), for each species' own count (speciesPlantCount).
  float lodCount = std::numeric_limits<float>::infinity();
  float nearestM = 0.0f;
  // While the imagery under it changes: the new imagery's weight 0 → 1 (terrain::SeedTriangle).
  // With a previous colour (classifyTriangle's previousColourAt) species cross-fade; without,
  // every group's fade is scaled by it (the plants grow in as the first imagery arrives).
  float imageryBlend = 1.0f;
};

// Each species stops its triangle's sequence at its own count (issue 18): its ground density
// over the triangle, thinned by the same level of detail,
//     N_s = min(N, min(lodCount, D_s · A)),
// A the triangle's area as a float (what the GPU is given: seedArea). A cluster of species s
// at index c is drawn with plantFade(N_s, C, c, seed) × speciesHorizonFade, so a sparse species
// (gravel) keeps only the first of the sequence's clusters that pick it: they are stratified, so
// its plants stay evenly spread, and they grow in and fade out by size as N_s moves, like any
// sequence end.
float speciesPlantCount(const Species& species, float plantCount, float lodCount, float areaM2);
// The size factor of a species' plants at distance nearestM: 1 within ¾ of its horizon, a
// smoothstep to 0 at it (terrain::horizonFade, in float as the GPU computes it). A size, not a
// count: every plant shrinks by at most 6 / horizon per metre the camera moves (0.04 % per cm at
// 150 m), where fading the count would shrink the last plant by D · A · 6 / horizon.
float speciesHorizonFade(const Species& species, float nearestM);
// The area the GPU is given for a triangle (float of the double area).
float seedArea(const std::array<glm::dvec3, 3>& vertices);

// The fade of the element `index` of a sequence shown up to `count`: 1 well inside, 0 beyond,
// and over the last kSequenceFadeShare of the sequence (at least one element) a ramp, so the
// end grows in over many elements instead of one: as the camera moves, count changes by about
// count · 2 / distance per metre (eq. 1), and each element's size then by at most
// 2 / (kSequenceFadeShare · distance) per metre — 0.4 % per centimetre at 5 m, where a one-element
// fade grew a whole cluster per centimetre near the camera (issue 18's 2 % bound).
inline constexpr float kSequenceFadeShare = 0.25f;
inline float sequenceFade(float count, uint32_t index) {
  const float w = count * kSequenceFadeShare > 1.0f ? count * kSequenceFadeShare : 1.0f;
  const float f = (count - static_cast<float>(index)) / w;
  return f <= 0.0f ? 0.0f : (f >= 1.0f ? 1.0f : f);
}
// Clusters a count N touches: 0 for N ≤ 0, else 1 + ⌈max(N − C, 0) / C⌉.
uint32_t clusterCount(float plantCount, uint32_t clusterSize);
// Work items of a triangle in the classify pass: one per seed of cluster 0 (each looks up its
// own species) and one per further cluster — ⌈min(N, C)⌉ + clusterCount − 1 (0 for N ≤ 0).
// Item k < ⌈min(N, C)⌉ is seed k of cluster 0, item k beyond is cluster k − ⌈min(N, C)⌉ + 1.
uint32_t classifyItems(float plantCount, uint32_t clusterSize);
// Fade of seed s of cluster c for count N.
float plantFade(float plantCount, uint32_t clusterSize, uint32_t cluster, uint32_t seed);

// Where a cluster's plants can be: its stratum (cluster 0: the whole triangle).
Stratum clusterStratumOf(uint64_t key, uint32_t cluster);
// Seed s of cluster c on the unit triangle (r′1, r′2), and the cluster centre.
glm::vec2 seedPoint(uint64_t key, uint32_t cluster, uint32_t seed);
glm::vec2 clusterCentre(uint64_t key, uint32_t cluster);

// What the imagery says under a point: its colour (linear RGB) and, where the dataset has a
// near-infrared layer, its NDVI (kNoNdvi otherwise). Made from a colour alone, NDVI is absent.
struct GroundSample {
  GroundSample(glm::vec3 linearColour, float ndviValue = kNoNdvi, SpeciesMask allowedSpecies = kAllSpecies)
      : linear(linearColour), ndvi(ndviValue), allowed(allowedSpecies) {}
  glm::vec3 linear;
  float ndvi;
  SpeciesMask allowed;  // the species the landcover class here allows (landcover_species.h)
};

// The ground under a point of the triangle given by (r′1, r′2).
using BaseColourAt = std::function<GroundSample(glm::vec2 rPrime)>;

// One classified group of plants, as the GPU appends it to its species' buffer: a whole cluster
// (c ≥ 1) or one seed of cluster 0.
struct PlantCluster {
  uint32_t triangle = 0;  // index of the triangle in the caller's list
  uint32_t cluster = 0;
  uint32_t firstSeed = 0;
  uint32_t seedCount = 0;  // plants shown (the last possibly faded)
  uint32_t species = 0;
  float sPrime = 0.0f;  // eq. 18
  float fade = 1.0f;    // of the cluster (c ≥ 1) or the seed (c = 0)
};

// The surviving groups of one triangle in sequence order (bare soil and no-score rejected).
// `previousColourAt` (may be empty): the colour under the imagery drawn before, while
// triangle.imageryBlend < 1. Each group then picks a species from both with the same draw: the
// same species keeps its plants (s′ mixed by the blend), different ones both appear, the
// previous one faded by (1 − blend), the new one by blend — a cross-fade by size, no switch.
void classifyTriangle(const SeedTriangleInput& triangle, uint32_t triangleIndex, const SpeciesCatalog& catalog,
                      const SeedingOptions& options, const BaseColourAt& colourAt, std::vector<PlantCluster>& out,
                      const BaseColourAt& previousColourAt = {});

// A plant with its parameters (what the species pipelines draw).
struct Plant {
  glm::dvec3 position{0.0};  // root, local ENU
  glm::vec2 rPrime{0.0f};    // on the triangle
  uint32_t triangle = 0, cluster = 0, seed = 0;
  uint32_t species = 0;
  float sPrime = 0.0f;
  float fade = 1.0f;       // size factor at the end of the sequence (1 at full density)
  float heightM = 0.0f;    // full-size height: the species range, scaled by s′ (sPrimeFactor)
  float stiffness = 0.0f;  // relative, k′ / k_c (blade_shape.h "Units")
  float widthM = 0.0f;
  float orientationRad = 0.0f;  // about the vertical, [0, 2π)
  float colourModulation = 0.0f;
};

// The plants of the groups `clusters` of `triangle`, appended to `out`.
void growPlants(const SeedTriangleInput& triangle, std::span<const PlantCluster> clusters,
                const SpeciesCatalog& catalog, const SeedingOptions& options, std::vector<Plant>& out);

}  // namespace vegstream::vegetation
