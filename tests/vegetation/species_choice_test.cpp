// vegetation/species_choice.h, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3
// eq. 16–18: the two-best pick, its frequencies under Philox draws, thresholds, bare soil, a
// synthetic base map with three regions, and the default catalog on real Zion colours.

#include "vegetation/species_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include "vegetation/philox.h"

namespace vegstream::vegetation {
namespace {

Species plant(const std::string& name, glm::vec3 hsv, RendererKind kind = RendererKind::Grass) {
  Species s;
  s.name = name;
  s.score = {hsv, {2.0f, 1.0f, 0.5f}, 3.0f};
  s.kind = kind;
  s.heightM = s.stiffness = s.widthM = s.colourModulation = {1.0f, 1.0f};
  return s;
}

Species bare(const std::string& name, glm::vec3 hsv) {
  Species s = plant(name, hsv);
  s.bare = true;
  return s;
}

int indexOf(const SpeciesCatalog& c, const std::string& name) {
  for (size_t i = 0; i < c.species.size(); ++i)
    if (c.species[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no species " << name;
  return -1;
}

float z(uint32_t i, uint32_t key = 0x1234abcdu) { return u01(philox(i, 0u, key).x); }

TEST(SpeciesChoice, HueWrapsAround) {
  SpeciesCatalog c{{plant("red", {355.0f / 360.0f, 0.6f, 0.5f}), plant("green", {0.33f, 0.6f, 0.5f})}};
  const SpeciesCandidates k = speciesCandidates(c, {5.0f / 360.0f, 0.6f, 0.5f});
  EXPECT_EQ(k.first, 0);
  EXPECT_LT(k.secondRatio, 1e-3f);
  EXPECT_EQ(chooseSpecies(c, {5.0f / 360.0f, 0.6f, 0.5f}, 0.5f).species, 0);
}

TEST(SpeciesChoice, OneSpeciesAlwaysWinsWithFullShare) {
  SpeciesCatalog c{{plant("only", {0.3f, 0.5f, 0.5f})}};
  const SpeciesChoice ch = chooseSpecies(c, {0.8f, 0.1f, 0.9f}, 0.0f);
  EXPECT_EQ(ch.species, 0);
  EXPECT_EQ(ch.secondRatio, 0.0f);
  EXPECT_EQ(ch.sPrime, 1.0f);
}

TEST(SpeciesChoice, TiesKeepTheLowerIndexFirst) {
  SpeciesCatalog c{{plant("a", {0.3f, 0.5f, 0.5f}), plant("b", {0.3f, 0.5f, 0.5f})}};
  const SpeciesCandidates k = speciesCandidates(c, {0.31f, 0.5f, 0.5f});
  EXPECT_EQ(k.first, 0);
  EXPECT_EQ(k.second, 1);
  EXPECT_FLOAT_EQ(k.secondRatio, 0.5f);
  EXPECT_EQ(chooseSpecies(c, {0.31f, 0.5f, 0.5f}, 0.49f).species, 1);  // z < ratio → second
  EXPECT_EQ(chooseSpecies(c, {0.31f, 0.5f, 0.5f}, 0.5f).species, 0);
}

// Over 10⁵ Philox draws the second best is picked with frequency s1 / (s0 + s1) (within 4σ).
TEST(SpeciesChoice, PickFrequencyFollowsTheScoreRatio) {
  SpeciesCatalog c{
      {plant("a", {0.30f, 0.5f, 0.5f}), plant("b", {0.36f, 0.5f, 0.5f}), plant("far", {0.8f, 0.9f, 0.9f})}};
  for (float h : {0.31f, 0.325f, 0.335f, 0.35f}) {
    const glm::vec3 hsv{h, 0.5f, 0.5f};
    const double s0 = colourScore(c.species[0].score, hsv), s1 = colourScore(c.species[1].score, hsv);
    const double pa = s0 / (s0 + s1), pb = 1.0 - pa;
    const double p2 = std::min(pa, pb);  // the second best's probability
    const SpeciesCandidates k = speciesCandidates(c, hsv);
    EXPECT_NEAR(k.secondRatio, p2, 1e-5);
    constexpr int n = 100000;
    int second = 0;
    for (int i = 0; i < n; ++i) {
      const SpeciesChoice ch = chooseSpecies(c, hsv, z(static_cast<uint32_t>(i)));
      ASSERT_TRUE(ch.species == 0 || ch.species == 1);
      second += ch.species == k.second ? 1 : 0;
      EXPECT_FLOAT_EQ(ch.sPrime, ch.species == k.second ? k.secondRatio : 1.0f - k.secondRatio);
    }
    EXPECT_NEAR(double(second) / n, p2, 4.0 * std::sqrt(p2 * (1.0 - p2) / n)) << "h " << h;
  }
}

TEST(SpeciesChoice, ThresholdsExcludeSpecies) {
  Species far = plant("far", {0.8f, 0.9f, 0.9f});
  SpeciesCatalog c{{plant("near", {0.3f, 0.5f, 0.5f}), far}};
  const glm::vec3 hsv{0.6f, 0.7f, 0.7f};
  // Without thresholds someone always wins.
  EXPECT_GE(chooseSpecies(c, hsv, 0.0f).species, 0);
  // A threshold above both scores: nothing is in, the seed is rejected.
  for (Species& s : c.species) s.threshold = 1e6f;
  const SpeciesChoice none = chooseSpecies(c, hsv, 0.0f);
  EXPECT_EQ(none.species, -1);
  EXPECT_EQ(speciesCandidates(c, hsv).first, -1);
  // Only "far" under its threshold: "near" wins alone, whatever z.
  c.species[0].threshold = 0.0f;
  const SpeciesCandidates k = speciesCandidates(c, hsv);
  EXPECT_EQ(k.first, 0);
  EXPECT_EQ(k.second, -1);
  EXPECT_EQ(chooseSpecies(c, hsv, 0.0f).species, 0);
  EXPECT_TRUE(passesThreshold(c.species[0], -100.0f));
  EXPECT_FALSE(passesThreshold(c.species[1], std::log(1e6f) - 0.01f));
  EXPECT_TRUE(passesThreshold(c.species[1], std::log(1e6f)));
}

TEST(SpeciesChoice, BareSoilRejects) {
  SpeciesCatalog c{{plant("grass", {0.3f, 0.5f, 0.5f}), bare("rock", {0.08f, 0.1f, 0.8f})}};
  for (uint32_t i = 0; i < 1000; ++i) EXPECT_EQ(chooseSpecies(c, {0.08f, 0.1f, 0.8f}, z(i)).species, -1);
  EXPECT_EQ(chooseSpecies(c, {0.3f, 0.5f, 0.5f}, 0.3f).species, 0);
}

// A synthetic base map over x in [0, 3): green (grass reference) for x < 1, red (gravel
// reference) for 1 ≤ x < 2, pale (pale sandstone reference) beyond, each perturbed with ±0.02
// noise per channel; in 1 ± 0.05 the colour blends linearly from green to red.
struct BaseMap {
  glm::vec3 green, red, pale;
  glm::vec3 at(float x, uint32_t i) const {
    const Philox2x32Out r = philox(i, 1u, 0xbeefu), r2 = philox(i, 2u, 0xbeefu);
    const glm::vec3 noise = (glm::vec3(u01(r.x), u01(r.y), u01(r2.x)) - 0.5f) * 0.04f;
    glm::vec3 c;
    if (x < 0.95f)
      c = green;
    else if (x < 1.05f)
      c = green + (red - green) * ((x - 0.95f) / 0.1f);  // hue: both near 0…0.25, no wrap between
    else if (x < 2.0f)
      c = red;
    else
      c = pale;
    c += noise;
    c.x = c.x < 0.0f ? c.x + 1.0f : c.x;
    return glm::clamp(c, glm::vec3(0.0f), glm::vec3(0.9999f, 1.0f, 1.0f));
  }
};

TEST(SpeciesChoice, SyntheticBaseMapFollowsItsRegions) {
  const SpeciesCatalog& cat = defaultSpeciesCatalog();
  const int grass = indexOf(cat, "grass"), gravel = indexOf(cat, "red gravel"), pale = indexOf(cat, "pale sandstone");
  const BaseMap map{cat.species[static_cast<size_t>(grass)].score.reference,
                    cat.species[static_cast<size_t>(gravel)].score.reference,
                    cat.species[static_cast<size_t>(pale)].score.reference};
  constexpr int n = 20000;
  int inGreen = 0, inRed = 0, inPale = 0;
  for (int i = 0; i < n; ++i) {
    const auto u = static_cast<uint32_t>(i);
    inGreen += chooseSpecies(cat, map.at(0.5f, u), z(u)).species == grass ? 1 : 0;
    inRed += chooseSpecies(cat, map.at(1.5f, u), z(u)).species == gravel ? 1 : 0;
    inPale += chooseSpecies(cat, map.at(2.5f, u), z(u)).species == -1 ? 1 : 0;
  }
  EXPECT_GE(inGreen, n * 95 / 100);
  EXPECT_GE(inRed, n * 95 / 100);
  EXPECT_EQ(inPale, n) << "pale sandstone is bare soil: everything there is rejected";

  // Across the green–red border the share of each follows the expected probability given the
  // colour at each point: the observed count of gravel against Σ P(gravel) within 4σ.
  // (Half way, the blended colour is a yellow brown: "dry tufts" takes part there, as on real
  // imagery; the test counts gravel against its own probability, whoever the other one is.)
  std::vector<int> gravelAcross;
  for (float x : {0.97f, 1.0f, 1.03f, 1.06f}) {
    double expected = 0.0, variance = 0.0;
    int observed = 0;
    for (int i = 0; i < n; ++i) {
      const auto u = static_cast<uint32_t>(i);
      const glm::vec3 hsv = map.at(x, u);
      const SpeciesCandidates k = speciesCandidates(cat, hsv);
      double p = 0.0;  // P(gravel) at this colour
      if (k.first == gravel) p = 1.0 - k.secondRatio;
      if (k.second == gravel) p = k.secondRatio;
      expected += p;
      variance += p * (1.0 - p);
      observed += chooseSpecies(cat, hsv, z(u, 0x77u)).species == gravel ? 1 : 0;
    }
    EXPECT_NEAR(observed, expected, 4.0 * std::sqrt(variance) + 1.0) << "x " << x;
    std::printf("border x %.2f: gravel %d of %d, expected %.1f\n", double(x), observed, n, expected);
    gravelAcross.push_back(observed);
  }
  EXPECT_LT(gravelAcross[0], n / 10) << "green side";
  EXPECT_GT(gravelAcross[3], n * 9 / 10) << "red side";
  EXPECT_LT(gravelAcross[1], gravelAcross[2]);
}

// The default catalog on real imagery colours, read with `vegstream query` off the imported
// Zion sample (out/datasets/zion): an olive plateau clearing (37.481, −113.044), the very dark
// forest canopy (37.419, −113.013), red sandstone (37.419, −113.168 and 37.326, −113.199), pale
// Navajo sandstone (37.202, −112.920).
TEST(SpeciesChoice, DefaultCatalogOnZionColours) {
  const SpeciesCatalog& cat = defaultSpeciesCatalog();
  auto best = [&](uint8_t r, uint8_t g, uint8_t b) {
    const SpeciesCandidates k = speciesCandidates(cat, hsvFromSrgb8(r, g, b));
    return k.first < 0 ? std::string("none") : cat.species[static_cast<size_t>(k.first)].name;
  };
  EXPECT_EQ(best(0x4a, 0x50, 0x42), "grass");
  EXPECT_EQ(best(0x1c, 0x24, 0x19), "conifer");
  EXPECT_EQ(best(0xc4, 0x8d, 0x86), "red gravel");
  EXPECT_EQ(best(0x79, 0x57, 0x50), "red gravel");
  EXPECT_EQ(best(0xd2, 0xc7, 0xb7), "pale sandstone");
  EXPECT_EQ(chooseSpecies(cat, hsvFromSrgb8(0xd2, 0xc7, 0xb7), 0.9f).species, -1);
  EXPECT_EQ(cat.species[static_cast<size_t>(indexOf(cat, "grass"))].kind, RendererKind::Grass);
  EXPECT_EQ(cat.species[static_cast<size_t>(indexOf(cat, "red gravel"))].kind, RendererKind::Gravel);
  EXPECT_TRUE(cat.species[static_cast<size_t>(indexOf(cat, "pale sandstone"))].bare);
}

}  // namespace
}  // namespace vegstream::vegetation
