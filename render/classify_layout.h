#pragma once
// Data shared by the CPU and the classify pass's shaders (shaders/common/classify_layout.glsl):
// std430 / std140 layouts, checked with static_assert. Plain data: callers above render/ fill
// SeedTriangleGpu and read VegetationFigures without seeing Vulkan.

#include <array>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "vegetation/species_catalog.h"

namespace vegstream::render {

// One seed triangle (std430). Positions relative to the frame's camera (the renderer draws
// camera-relative), imagery uv in its layer's [0, 1]² (−1 layer: no imagery, no plants).
struct SeedTriangleGpu {
  glm::vec4 v0{0.0f};             // xyz apex (m); w: plant count N (eq. 1/2)
  glm::vec4 v1{0.0f};             // xyz left
  glm::vec4 v2{0.0f};             // xyz right
  glm::vec4 uv01{0.0f};           // uv of the apex (xy) and the left vertex (zw)
  glm::vec2 uv2{0.0f};            // uv of the right vertex
  uint32_t keyLo = 0, keyHi = 0;  // the triangle's identity (Philox key, counter word)
  int32_t layer = -1;
  float lodCount = 0.0f;  // eq. 1 / 2 (terrain::SeedTriangle): each species' own count
  float areaM2 = 0.0f;    // vegetation::seedArea                  (vegetation::speciesPlantCount)
  float nearestM = 0.0f;  // to the camera's nearest vertex
  // The imagery drawn before it while it changes (terrain::SeedTriangle): plants cross-fade.
  glm::vec4 previousUv01{0.0f};
  glm::vec2 previousUv2{0.0f};
  int32_t previousLayer = -1;
  float imageryBlend = 1.0f;  // the weight of `layer`'s species (and, without a previous layer, the fade-in)
};
static_assert(sizeof(SeedTriangleGpu) == 128);

// One classified group (std430): a cluster, or one seed of cluster 0
// (vegetation::PlantCluster).
struct PlantClusterGpu {
  uint32_t triangle = 0, cluster = 0, firstSeed = 0, seedCount = 0;
  uint32_t species = 0;
  float sPrime = 0.0f;
  float fade = 0.0f;
  uint32_t pad = 0;
};
static_assert(sizeof(PlantClusterGpu) == 32);

// One species (std140, an array of kMaxSpecies in SpeciesBlock).
struct SpeciesGpu {
  glm::vec4 reference{0.0f};        // HSV, w: p
  glm::vec4 weights{0.0f};          // HSV weights, w: ln threshold (−1e30: none)
  std::array<uint32_t, 4> flags{};  // x: bare, y: renderer kind, z: casts planar shadows
  glm::vec4 heightStiffness{0.0f};  // height min/max (m), k′ min/max
  glm::vec4 widthColour{0.0f};      // width min/max (m), colour modulation min/max
  glm::vec4 marker{0.0f};           // linear RGB of the classification markers, w: phototropism
  glm::vec4 ground{0.0f};           // x: plants per m², y: horizon (m), z: NDVI reference, w: NDVI weight
  glm::vec4 index{0.0f};            // x: excess-green reference, y: its weight
};
static_assert(sizeof(SpeciesGpu) == 128);

struct SpeciesBlock {
  std::array<SpeciesGpu, vegetation::kMaxSpecies> species{};
  std::array<uint32_t, 4> count{};  // x: species in the catalog
  std::array<glm::vec4, 3> calibration{};  // the catalog's colour calibration, rows (xyz M, w offset)
  // The catalog's landcoverCodes (code c at [c / 4][c % 4]); every bit set without them.
  std::array<std::array<uint32_t, 4>, 64> landcoverMasks{};
};
static_assert(sizeof(SpeciesBlock) == 128 * vegetation::kMaxSpecies + 16 + 48 + 1024);

// The catalog (and its colour calibration) as the GPU reads it.
SpeciesBlock packSpecies(const vegetation::SpeciesCatalog& catalog);

}  // namespace vegstream::render
