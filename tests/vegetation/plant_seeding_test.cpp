// vegetation/plant_seeding.h: uniform and compact clustered seeding (core seed 001 §3.4),
// a plant sequence that only grows at its end (density changes never move plants), and species
// picked from the base colour at the plant level (§3.3).

#include <algorithm>
#include <span>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "core/hash.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_choice.h"
#include "vegetation/plant_seeding.h"

namespace vegstream::vegetation {
namespace {

// The upper 1 % point of χ² with k degrees of freedom (Wilson–Hilferty).
double chiSquare99(double k) {
  const double z = 2.326347874;
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

// Cell of (r′1, r′2) among the k² congruent sub-triangles of the unit triangle.
int cellOf(glm::vec2 r, int k) {
  const float x = r.x * static_cast<float>(k), y = r.y * static_cast<float>(k);
  const int i = std::clamp(static_cast<int>(x), 0, k - 1), j = std::clamp(static_cast<int>(y), 0, k - 1);
  const bool upper = (x - static_cast<float>(i)) + (y - static_cast<float>(j)) >= 1.0f;
  return (i * k + j) * 2 + (upper ? 1 : 0);
}

// χ² of plant positions over the k² sub-triangles (cells outside the triangle never fill: the
// statistic runs over the k² real ones, each of area 1 / k²).
double chiSquare(const std::vector<glm::vec2>& points, int k, int* dof) {
  std::map<int, double> counts;
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      counts[(i * k + j) * 2] = 0.0;
      if (i + j < k - 1) counts[(i * k + j) * 2 + 1] = 0.0;
    }
  for (glm::vec2 p : points) {
    const auto it = counts.find(cellOf(p, k));
    EXPECT_NE(it, counts.end()) << p.x << " " << p.y;
    if (it != counts.end()) it->second += 1.0;
  }
  EXPECT_EQ(counts.size(), size_t(k) * size_t(k));
  const double expected = static_cast<double>(points.size()) / static_cast<double>(counts.size());
  double chi = 0.0;
  for (const auto& [cell, n] : counts) chi += (n - expected) * (n - expected) / expected;
  *dof = static_cast<int>(counts.size()) - 1;
  return chi;
}

// Every seed of the first `plants` plants of triangle `key` (the end of the sequence faded in part).
std::vector<glm::vec2> seeds(uint64_t key, float plants, uint32_t clusterSize) {
  std::vector<glm::vec2> out;
  const uint32_t clusters = clusterCount(plants, clusterSize);
  for (uint32_t c = 0; c < clusters; ++c)
    for (uint32_t s = 0; s < clusterSize; ++s)
      if (plantFade(plants, clusterSize, c, s) > 0.0f) out.push_back(seedPoint(key, c, s));  // grown at all
  return out;
}

TEST(PlantSeeding, PositionsPassChiSquareOnOneTriangleClusteredAndUnclustered) {
  // Clustered (C = 8, 650 clusters = P_12: complete levels) and unclustered (C = 1), one triangle.
  for (uint32_t size : {8u, 1u}) {
    const float n = static_cast<float>(size) * static_cast<float>(pyramidalNumber(12));
    const std::vector<glm::vec2> pts = seeds(0x1234'5678'9abc'def0ull, n, size);
    ASSERT_EQ(pts.size(), static_cast<size_t>(n));
    int dof = 0;
    const double chi = chiSquare(pts, 6, &dof);
    EXPECT_LT(chi, chiSquare99(dof)) << "C = " << size << ", " << pts.size() << " plants";
  }
}

TEST(PlantSeeding, PartlyFilledLevelsStayUniformOverManyTriangles) {
  // 400 triangles of 37 plants (C = 4: cluster 0 plus 8 clusters, level 3 partly filled).
  for (uint32_t size : {4u, 1u}) {
    std::vector<glm::vec2> pts;
    for (uint64_t key = 1; key <= 400; ++key) {
      const auto s = seeds(key * 0x9E3779B97F4A7C15ull, 37.0f, size);
      pts.insert(pts.end(), s.begin(), s.end());
    }
    int dof = 0;
    const double chi = chiSquare(pts, 8, &dof);
    EXPECT_LT(chi, chiSquare99(dof)) << "C = " << size;
  }
}

TEST(PlantSeeding, ClustersShrinkAsOneOverTheSquareRootOfTheirLevelsClusterCount) {
  // Mean distance of a seed to its cluster centre, per level n (n² clusters): × n it is constant.
  const uint32_t size = 8;
  std::vector<double> scaled;
  for (uint32_t level = 2; level <= 14; level += 3) {
    double sum = 0.0;
    int count = 0;
    for (uint64_t key = 1; key <= 20; ++key)
      for (uint32_t c = pyramidalNumber(level - 1); c < pyramidalNumber(level); ++c) {
        const glm::vec2 centre = clusterCentre(key, c);
        for (uint32_t s = 0; s < size; ++s) {
          sum += glm::length(glm::dvec2(seedPoint(key, c, s) - centre));
          ++count;
        }
      }
    const double mean = sum / count;
    scaled.push_back(mean * level);
    // Two uniform points of a right isosceles triangle with legs 1/n (a level's cell) are
    // 0.414/n apart on average (Monte Carlo, 4·10⁵ pairs).
    EXPECT_NEAR(mean * level, 0.414, 0.06) << "level " << level;
  }
  for (size_t i = 1; i < scaled.size(); ++i) EXPECT_NEAR(scaled[i] / scaled[0], 1.0, 0.15);
}

SpeciesCatalog threeSpecies() {
  SpeciesCatalog c;
  auto make = [](const char* name, glm::vec3 hsv, bool bare, RendererKind kind) {
    Species s;
    s.name = name;
    s.score = {hsv, glm::vec3(1.0f, 1.0f, 0.5f), 3.0f};
    s.bare = bare;
    s.kind = kind;
    s.heightM = {0.3f, 0.6f};
    s.stiffness = {1.0f, 4.0f};
    s.widthM = {0.01f, 0.02f};
    s.colourModulation = {0.9f, 1.1f};
    return s;
  };
  c.species.push_back(make("grass", {0.25f, 0.5f, 0.45f}, false, RendererKind::Grass));
  c.species.push_back(make("gravel", {0.03f, 0.45f, 0.55f}, false, RendererKind::Gravel));
  c.species.push_back(make("pale", {0.10f, 0.12f, 0.85f}, true, RendererKind::Grass));
  return c;
}

glm::vec3 linearFromHsv(glm::vec3 hsv) {
  const glm::vec3 s = srgbFromHsv(hsv);
  return {srgbDecode(s.r), srgbDecode(s.g), srgbDecode(s.b)};
}

TEST(PlantSeeding, SPrimeMakesMinorityPlantsSmallerThinnerAndSofter) {
  // Eq. 18's s′ modulates size and stiffness (seed 001 §3.3): the same plant (same triangle,
  // cluster, seed) at s′ = 0 has sPrimeFactor(lo, 0) = lo of its height, width and stiffness at
  // s′ = 1, and half-way in between at s′ = 0.5.
  const SpeciesCatalog catalog = threeSpecies();
  SeedTriangleInput t;
  t.key = 0x1234abcdull;
  t.vertices = {glm::dvec3(0, 0, 0), glm::dvec3(6, 0, 0), glm::dvec3(0, 6, 0)};
  t.plantCount = 40.0f;
  auto grow = [&](float sPrime) {
    const PlantCluster g{0, 2, 0, 8, 0, sPrime, 1.0f};
    std::vector<Plant> out;
    growPlants(t, std::span(&g, 1), catalog, SeedingOptions{}, out);
    return out;
  };
  const std::vector<Plant> minority = grow(0.0f), half = grow(0.5f), dominant = grow(1.0f);
  ASSERT_EQ(minority.size(), 8u);
  ASSERT_EQ(dominant.size(), 8u);
  for (size_t i = 0; i < minority.size(); ++i) {
    EXPECT_EQ(minority[i].position, dominant[i].position);
    EXPECT_FLOAT_EQ(minority[i].heightM, kSPrimeHeightLo * dominant[i].heightM);
    EXPECT_FLOAT_EQ(minority[i].widthM, kSPrimeWidthLo * dominant[i].widthM);
    EXPECT_FLOAT_EQ(minority[i].stiffness, kSPrimeStiffnessLo * dominant[i].stiffness);
    EXPECT_FLOAT_EQ(half[i].heightM, 0.5f * (minority[i].heightM + dominant[i].heightM));
    EXPECT_FLOAT_EQ(minority[i].orientationRad, dominant[i].orientationRad);
  }
}

TEST(PlantSeeding, MorePlantsOnlyAddToTheEndOfTheSequence) {
  const SpeciesCatalog catalog = threeSpecies();
  SeedTriangleInput t;
  t.key = 0xfeedfacecafebeefull;
  t.vertices = {glm::dvec3(0, 0, 0), glm::dvec3(6, 0, 0), glm::dvec3(0, 6, 0)};
  // A colour that changes across the triangle, so species differ between clusters.
  const BaseColourAt colour = [](glm::vec2 r) {
    return r.x < 0.5f ? linearFromHsv({0.25f, 0.5f, 0.45f}) : linearFromHsv({0.03f, 0.45f, 0.55f});
  };
  const SeedingOptions options;
  std::vector<Plant> previous;
  for (float n = 0.5f; n < 300.0f; n *= 1.37f) {
    t.plantCount = n;
    std::vector<PlantCluster> groups;
    classifyTriangle(t, 0, catalog, options, colour, groups);
    std::vector<Plant> plants;
    growPlants(t, groups, catalog, options, plants);
    // Every plant of the smaller count is still there, same place, species and size (except
    // the one that was fading in, which only grew).
    size_t matched = 0;
    for (const Plant& p : previous) {
      const auto it = std::find_if(plants.begin(), plants.end(),
                                   [&](const Plant& q) { return q.cluster == p.cluster && q.seed == p.seed; });
      ASSERT_NE(it, plants.end()) << "plant lost at N = " << n;
      EXPECT_EQ(it->position, p.position);
      EXPECT_EQ(it->species, p.species);
      EXPECT_EQ(it->heightM, p.heightM);
      EXPECT_GE(it->fade, p.fade);
      ++matched;
    }
    EXPECT_EQ(matched, previous.size());
    EXPECT_GE(plants.size(), previous.size());
    for (const Plant& p : plants) {
      EXPECT_GT(p.fade, 0.0f);
      EXPECT_LE(p.fade, 1.0f);
    }
    previous = plants;
  }
  // Same inputs, same plants; another triangle, other plants.
  std::vector<PlantCluster> again;
  classifyTriangle(t, 0, catalog, options, colour, again);
  std::vector<Plant> plantsAgain;
  growPlants(t, again, catalog, options, plantsAgain);
  ASSERT_EQ(plantsAgain.size(), previous.size());
  for (size_t i = 0; i < previous.size(); ++i) EXPECT_EQ(plantsAgain[i].position, previous[i].position);
  t.key ^= 1;
  std::vector<PlantCluster> other;
  classifyTriangle(t, 0, catalog, options, colour, other);
  std::vector<Plant> otherPlants;
  growPlants(t, other, catalog, options, otherPlants);
  ASSERT_FALSE(otherPlants.empty());
  EXPECT_NE(otherPlants[0].position, previous[0].position);
}

TEST(PlantSeeding, SpeciesFollowTheBaseMapRegions) {
  // A 300 m strip: green (x < 100), a 20 m green→red blend, red (120 … 200), pale (x > 200).
  SpeciesCatalog catalog = threeSpecies();
  for (Species& s : catalog.species) s.densityM2 = 100.0f;  // no species stops before N = 200 (12.5 m²)
  const glm::vec3 green{0.25f, 0.5f, 0.45f}, red{0.03f, 0.45f, 0.55f}, pale{0.10f, 0.12f, 0.85f};
  auto hsvAt = [&](double x) -> glm::vec3 {
    if (x < 100.0) return green;
    if (x < 120.0) return glm::mix(green, red, static_cast<float>((x - 100.0) / 20.0));
    if (x < 200.0) return red;
    return pale;
  };
  std::map<int, std::array<int, 4>> byZone;  // zone → counts of grass, gravel, (bare), rejected
  double expectedSecond = 0.0, observedSecond = 0.0, borderClusters = 0.0;
  const SeedingOptions options;
  uint64_t key = 77;
  for (double x0 = 0.0; x0 < 300.0; x0 += 5.0)
    for (double y0 = 0.0; y0 < 40.0; y0 += 5.0) {
      SeedTriangleInput t;
      t.key = mix32(static_cast<uint32_t>(key)) | (uint64_t{mix32(static_cast<uint32_t>(key) ^ 0xabcdu)} << 32);
      ++key;
      t.vertices = {glm::dvec3(x0, y0, 0), glm::dvec3(x0 + 5, y0, 0), glm::dvec3(x0, y0 + 5, 0)};
      t.plantCount = 200.0f;
      const auto worldX = [&](glm::vec2 r) {
        return pointOnTriangle(t.vertices[0], t.vertices[1], t.vertices[2], r).x;
      };
      const BaseColourAt colour = [&](glm::vec2 r) { return linearFromHsv(hsvAt(worldX(r))); };
      const uint32_t clusters = clusterCount(t.plantCount, options.clusterSize);
      std::vector<PlantCluster> groups;
      classifyTriangle(t, 0, catalog, options, colour, groups);
      for (uint32_t c = 1; c < clusters; ++c) {
        const double x = worldX(clusterCentre(t.key, c));
        const int zone = x < 95.0 ? 0 : (x >= 125.0 && x < 195.0 ? 1 : (x >= 205.0 ? 2 : -1));
        const auto it =
            std::find_if(groups.begin(), groups.end(), [&](const PlantCluster& g) { return g.cluster == c; });
        const int picked = it == groups.end() ? 3 : static_cast<int>(it->species);
        if (zone >= 0) ++byZone[zone][static_cast<size_t>(picked)];
        if (x > 106.0 && x < 114.0) {  // inside the blend: grass and gravel both score
          const SpeciesChoice choice = chooseSpecies(catalog, hsvFromLinear(linearFromHsv(hsvAt(x))), 2.0f);
          EXPECT_GE(choice.species, 0);
          expectedSecond += choice.secondRatio;
          borderClusters += 1.0;
          const glm::vec3 hsv = hsvFromLinear(linearFromHsv(hsvAt(x)));
          const int second =
              logColourScore(catalog.species[0].score, hsv) >= logColourScore(catalog.species[1].score, hsv) ? 1 : 0;
          if (picked == second) observedSecond += 1.0;
        }
      }
    }
  auto share = [&](int zone, int species) {
    const auto& c = byZone[zone];
    return static_cast<double>(c[static_cast<size_t>(species)]) / (c[0] + c[1] + c[2] + c[3]);
  };
  EXPECT_GE(share(0, 0), 0.95) << "green region grows grass";
  EXPECT_GE(share(1, 1), 0.95) << "red region grows gravel";
  EXPECT_EQ(share(2, 3), 1.0) << "pale region grows nothing";
  ASSERT_GT(borderClusters, 250.0);
  const double sigma = std::sqrt(expectedSecond);  // Poisson-binomial, at most this
  EXPECT_NEAR(observedSecond, expectedSecond, 4.0 * sigma + 1.0)
      << "border mix: " << observedSecond << " of " << borderClusters << " took the second species";
}


// Issue 18: each species stops the triangle's sequence at its own count — its density over the
// triangle's area, the same level of detail, its own horizon — never beyond the triangle's N.
TEST(PlantSeeding, EachSpeciesStopsAtItsOwnDensityLevelOfDetailAndHorizon) {
  Species sparse;
  sparse.densityM2 = 2.0f;
  sparse.horizonM = 100.0f;
  Species dense = sparse;
  dense.densityM2 = 400.0f;
  const float area = 24.0f, inf = std::numeric_limits<float>::infinity();
  // Full detail at the camera: the density decides, capped by N.
  EXPECT_FLOAT_EQ(speciesPlantCount(sparse, 9600.0f, inf, area), 48.0f);
  EXPECT_FLOAT_EQ(speciesPlantCount(dense, 9600.0f, inf, area), 9600.0f);
  EXPECT_FLOAT_EQ(speciesPlantCount(dense, 500.0f, inf, area), 500.0f);
  // The level of detail thins both alike.
  EXPECT_FLOAT_EQ(speciesPlantCount(sparse, 9600.0f, 30.0f, area), 30.0f);
  EXPECT_FLOAT_EQ(speciesPlantCount(dense, 9600.0f, 30.0f, area), 30.0f);
  // The horizon is a size: whole within ¾ of it, half at ⅞, none at it and beyond; moving the
  // camera 1 cm changes every plant's size by less than 2 % of its full size (issue 18).
  EXPECT_EQ(speciesHorizonFade(sparse, 75.0f), 1.0f);
  EXPECT_NEAR(speciesHorizonFade(sparse, 87.5f), 0.5f, 1e-6f);
  EXPECT_EQ(speciesHorizonFade(sparse, 100.0f), 0.0f);
  EXPECT_EQ(speciesHorizonFade(sparse, 150.0f), 0.0f);
  float last = speciesHorizonFade(sparse, 70.0f);
  for (float d = 70.0f; d <= 101.0f; d += 0.01f) {
    const float f = speciesHorizonFade(sparse, d);
    EXPECT_LE(std::abs(f - last), 0.02f) << d;
    last = f;
  }

  // On a triangle of grass and gravel, the gravel clusters past the gravel's own count are
  // dropped, the grass ones kept: the gravel keeps the first of the sequence, evenly spread.
  SpeciesCatalog catalog = threeSpecies();
  catalog.species[0].densityM2 = 400.0f;  // grass
  catalog.species[1].densityM2 = 4.0f;    // gravel
  SeedTriangleInput t;
  t.key = 0x1234567890abcdefull;
  t.vertices = {glm::dvec3(0, 0, 0), glm::dvec3(8, 0, 0), glm::dvec3(0, 6, 0)};  // 24 m²
  t.plantCount = 2000.0f;
  const glm::vec3 green{0.25f, 0.5f, 0.45f}, red{0.03f, 0.45f, 0.55f};
  const BaseColourAt colour = [&](glm::vec2 r) { return linearFromHsv(r.x < 0.5f ? green : red); };
  std::vector<PlantCluster> groups;
  classifyTriangle(t, 0, catalog, SeedingOptions{}, colour, groups);
  float grass = 0.0f, gravel = 0.0f;
  for (const PlantCluster& g : groups) (g.species == 0 ? grass : gravel) += g.fade * float(g.seedCount);
  EXPECT_NEAR(gravel, 96.0f * 0.25f, 14.0f) << "a quarter of the first 96 plants' area is red";
  EXPECT_GT(grass, 1000.0f);
}

}  // namespace
}  // namespace vegstream::vegetation
