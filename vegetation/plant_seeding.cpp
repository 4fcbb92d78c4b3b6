// Plants of a seed triangle, core seed 001_3eca9f2c7752e4fb.txt §2.2, §3.3, §3.4 (see the
// header). Operation for operation the same as shaders/classify.comp + shaders/common/seeding.glsl.
#include "vegetation/plant_seeding.h"
#include "vegetation/overflow_thinning.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

#include "vegetation/colour_score.h"
#include "vegetation/philox.h"
#include "vegetation/species_choice.h"

namespace vegstream::vegetation {
namespace {

constexpr float kTwoPi = 6.28318530717958647692f;

Philox2x32Out draw(uint64_t key, uint32_t cluster, uint32_t slot) {
  assert(cluster < kMaxClustersPerTriangle && slot < 256);
  return philox((cluster << 8) | slot, static_cast<uint32_t>(key >> 32), static_cast<uint32_t>(key));
}

float mixRange(const FloatRange& r, float u) { return r.min + (r.max - r.min) * u; }

}  // namespace

uint32_t clusterCount(float plantCount, uint32_t clusterSize) {
  assert(clusterSize >= 1 && clusterSize <= kMaxClusterSize);
  if (!(plantCount > 0.0f)) return 0;
  const float c = static_cast<float>(clusterSize);
  const float rest = std::max(plantCount - c, 0.0f) / c;
  return 1u + static_cast<uint32_t>(std::ceil(rest));
}

uint32_t classifyItems(float plantCount, uint32_t clusterSize) {
  const uint32_t clusters = clusterCount(plantCount, clusterSize);
  if (clusters == 0) return 0;
  const auto seeds = static_cast<uint32_t>(std::ceil(std::min(plantCount, static_cast<float>(clusterSize))));
  return seeds + clusters - 1;
}

float plantFade(float plantCount, uint32_t clusterSize, uint32_t cluster, uint32_t seed) {
  const float c = static_cast<float>(clusterSize);
  if (cluster == 0) return sequenceFade(std::min(plantCount, c), seed);
  return sequenceFade(std::max(plantCount - c, 0.0f) / c, cluster - 1);
}

float speciesPlantCount(const Species& species, float plantCount, float lodCount, float areaM2) {
  return std::min(plantCount, std::min(lodCount, species.densityM2 * areaM2));
}

float speciesHorizonFade(const Species& species, float nearestM) {
  assert(species.horizonM > 0.0f);
  const float t = std::clamp((nearestM - 0.75f * species.horizonM) / (0.25f * species.horizonM), 0.0f, 1.0f);
  return 1.0f - t * t * (3.0f - 2.0f * t);
}

float seedArea(const std::array<glm::dvec3, 3>& v) {
  return static_cast<float>(0.5 * glm::length(glm::cross(v[1] - v[0], v[2] - v[0])));
}

Stratum clusterStratumOf(uint64_t key, uint32_t cluster) {
  if (cluster == 0) return {};
  const uint32_t level = clusterLevel(cluster + 1);
  return clusterStratum(cluster, draw(key, level, philox_slot::kLevelOffset).x);
}

glm::vec2 seedPoint(uint64_t key, uint32_t cluster, uint32_t seed) {
  assert(seed < kMaxClusterSize);
  const Philox2x32Out r = draw(key, cluster, philox_slot::kPosition + seed);
  return pointInStratum(clusterStratumOf(key, cluster), {u01(r.x), u01(r.y)});
}

glm::vec2 clusterCentre(uint64_t key, uint32_t cluster) {
  const Philox2x32Out r = draw(key, cluster, philox_slot::kCentre);
  return pointInStratum(clusterStratumOf(key, cluster), {u01(r.x), u01(r.y)});
}

void classifyTriangle(const SeedTriangleInput& triangle, uint32_t triangleIndex, const SpeciesCatalog& catalog,
                      const SeedingOptions& options, const BaseColourAt& colourAt, std::vector<PlantCluster>& out,
                      const BaseColourAt& previousColourAt) {
  const uint32_t size = options.clusterSize;
  const uint32_t clusters = clusterCount(triangle.plantCount, size);
  const float area = seedArea(triangle.vertices);
  const bool crossFade = previousColourAt && triangle.imageryBlend < 1.0f;
  // Appends the group as `pick` with weight w on its fade: nothing for bare soil or a fade of 0
  // (beyond its species' own count).
  auto append = [&](const SpeciesChoice& pick, float w, uint32_t c, uint32_t firstSeed, uint32_t count) {
    if (pick.species < 0) return;
    const Species& sp = catalog.species[size_t(pick.species)];
    const float n = speciesPlantCount(sp, triangle.plantCount, triangle.lodCount, area);
    const float fade = plantFade(n, size, c, firstSeed) * speciesHorizonFade(sp, triangle.nearestM) * w *
                       thinningFade(options.thinning[size_t(pick.species)], groupPriority(triangle.key, c, firstSeed));
    if (fade <= 0.0f) return;
    out.push_back({triangleIndex, c, firstSeed, count, static_cast<uint32_t>(pick.species), pick.sPrime, fade});
  };
  // Trees grow on their own grid (tree_placement.h): a seed that picks a tree species grows no
  // plant where the tree would stand (the forest floor), else the other of the two best
  // (choosePlantSpecies; render/classify_layout flags tree species for the GPU's twin).
  const auto choose = [&](const GroundSample& g, float z) {
    return choosePlantSpeciesAt(catalog, g.linear, z, g.ndvi, g.allowed);
  };
  // The vertices relative to the canopy's camera, as the GPU has them (SeedTriangleGpu).
  glm::vec3 rel[3]{};
  if (options.canopy)
    for (int k = 0; k < 3; ++k) rel[k] = glm::vec3(triangle.vertices[size_t(k)] - options.canopy->camera);
  auto group = [&](glm::vec2 r, float z, uint32_t c, uint32_t firstSeed, uint32_t count) {
    if (options.canopy) {  // under a crown the group thins out (canopy_cells.h)
      const glm::vec3 p = rel[0] + r.x * (rel[1] - rel[0]) + r.y * (rel[2] - rel[0]);
      const float cover = canopyCover(*options.canopy, glm::vec2(p));
      if (cover > 0.0f && u01(draw(triangle.key, c, philox_slot::kCanopy + firstSeed).x) < kCanopyThinning * cover)
        return;
    }
    const GroundSample now = colourAt(r);
    SpeciesChoice pick = choose(now, z);
    float w = triangle.imageryBlend;
    if (crossFade) {
      const GroundSample then = previousColourAt(r);
      const SpeciesChoice before = choose(then, z);
      if (before.species == pick.species) {
        pick.sPrime = before.sPrime + (pick.sPrime - before.sPrime) * w;  // GLSL mix
        w = 1.0f;
      } else {
        append(before, 1.0f - w, c, firstSeed, count);
      }
    }
    append(pick, w, c, firstSeed, count);
  };
  for (uint32_t c = 0; c < clusters; ++c) {
    if (c == 0) {
      // Unclustered: each seed of cluster 0 chooses at its own root.
      const auto seeds = static_cast<uint32_t>(std::ceil(std::min(triangle.plantCount, static_cast<float>(size))));
      for (uint32_t s = 0; s < seeds; ++s)
        group(seedPoint(triangle.key, 0, s), u01(draw(triangle.key, 0, philox_slot::kColourSpecies + s).y), 0, s, 1);
      continue;
    }
    group(clusterCentre(triangle.key, c), u01(draw(triangle.key, c, philox_slot::kSpecies).x), c, 0, size);
  }
}

void growPlants(const SeedTriangleInput& triangle, std::span<const PlantCluster> clusters,
                const SpeciesCatalog& catalog, const SeedingOptions& options, std::vector<Plant>& out) {
  (void)options;
  const auto& v = triangle.vertices;
  for (const PlantCluster& g : clusters) {
    const Species& sp = catalog.species[g.species];
    for (uint32_t s = g.firstSeed; s < g.firstSeed + g.seedCount; ++s) {
      Plant p;
      p.rPrime = seedPoint(triangle.key, g.cluster, s);
      p.position = pointOnTriangle(v[0], v[1], v[2], p.rPrime);
      p.triangle = g.triangle;
      p.cluster = g.cluster;
      p.seed = s;
      p.species = g.species;
      p.sPrime = g.sPrime;
      p.fade = g.fade;
      const Philox2x32Out hs = draw(triangle.key, g.cluster, philox_slot::kHeightStiffness + s);
      const Philox2x32Out ow = draw(triangle.key, g.cluster, philox_slot::kOrientationWidth + s);
      const Philox2x32Out cm = draw(triangle.key, g.cluster, philox_slot::kColourSpecies + s);
      // A plant of a minority species at a border is smaller, thinner and softer: s′ near 0
      // (eq. 18; species_catalog.h sPrimeFactor).
      p.heightM = mixRange(sp.heightM, u01(hs.x)) * sPrimeFactor(kSPrimeHeightLo, g.sPrime);
      p.stiffness = mixRange(sp.stiffness, u01(hs.y)) * sPrimeFactor(kSPrimeStiffnessLo, g.sPrime);
      p.orientationRad = kTwoPi * u01(ow.x);
      p.widthM = mixRange(sp.widthM, u01(ow.y)) * sPrimeFactor(kSPrimeWidthLo, g.sPrime);
      p.colourModulation = mixRange(sp.colourModulation, u01(cm.x));
      out.push_back(p);
    }
  }
}

}  // namespace vegstream::vegetation
