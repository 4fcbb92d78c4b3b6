// Plants of a seed triangle, core seed 001_3eca9f2c7752e4fb.txt §2.2, §3.3, §3.4 (see the
// header). Operation for operation the same as shaders/classify.comp + shaders/common/seeding.glsl.
#include "vegetation/plant_seeding.h"

#include <cassert>
#include <cmath>

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
                      const SeedingOptions& options, const BaseColourAt& colourAt, std::vector<PlantCluster>& out) {
  const uint32_t size = options.clusterSize;
  const uint32_t clusters = clusterCount(triangle.plantCount, size);
  for (uint32_t c = 0; c < clusters; ++c) {
    if (c == 0) {
      // Unclustered: each seed of cluster 0 chooses at its own root.
      const auto seeds = static_cast<uint32_t>(std::ceil(std::min(triangle.plantCount, static_cast<float>(size))));
      for (uint32_t s = 0; s < seeds; ++s) {
        const float z = u01(draw(triangle.key, 0, philox_slot::kColourSpecies + s).y);
        const SpeciesChoice pick = chooseSpecies(catalog, hsvFromLinear(colourAt(seedPoint(triangle.key, 0, s))), z);
        if (pick.species < 0) continue;
        out.push_back({triangleIndex, 0, s, 1, static_cast<uint32_t>(pick.species), pick.sPrime,
                       plantFade(triangle.plantCount, size, 0, s)});
      }
      continue;
    }
    const float z = u01(draw(triangle.key, c, philox_slot::kSpecies).x);
    const SpeciesChoice pick = chooseSpecies(catalog, hsvFromLinear(colourAt(clusterCentre(triangle.key, c))), z);
    if (pick.species < 0) continue;
    out.push_back({triangleIndex, c, 0, size, static_cast<uint32_t>(pick.species), pick.sPrime,
                   plantFade(triangle.plantCount, size, c, 0)});
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
