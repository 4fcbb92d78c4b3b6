// Tree species by colour and site (vegetation/tree_niche.h; issue 41 item 4): the softened
// envelope, the default catalog's species each winning on its own ground under the same forest
// colour, claims_ground keeping a species out of the first choice, and the catalog's checks.

#include <cmath>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "vegetation/colour_score.h"
#include "vegetation/species_catalog.h"
#include "vegetation/species_choice.h"
#include "vegetation/tree_niche.h"

namespace vegstream::vegetation {
namespace {

const SpeciesCatalog& catalog() { return defaultSpeciesCatalog(); }

int indexOf(const std::string& name) {
  for (size_t i = 0; i < catalog().species.size(); ++i)
    if (catalog().species[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no species " << name;
  return -1;
}

TEST(TreeNiche, InsideIsZeroOutsideFallsOffByTheSoftWidthUnknownIsZero) {
  TreeNiche n;
  n.elevationM[0] = 1000.0f;
  n.elevationM[1] = 2000.0f;
  n.slopeDeg[1] = 20.0f;
  TreeSite s;
  s.elevationM = 1500.0f;
  s.slopeDeg = 10.0f;
  EXPECT_EQ(logNicheFit(n, s), 0.0f);
  s.elevationM = 2000.0f + kElevationSoftM;  // one soft width above
  EXPECT_FLOAT_EQ(logNicheFit(n, s), -1.0f);
  s.slopeDeg = 20.0f + 2.0f * kSlopeSoftDeg;  // and two soft widths too steep
  EXPECT_FLOAT_EQ(logNicheFit(n, s), -5.0f);
  EXPECT_EQ(logNicheFit(n, TreeSite{}), 0.0f) << "an unknown site counts nothing";
  EXPECT_EQ(logNicheFit(TreeNiche{}, s), 0.0f) << "no niche: anywhere";
}

TEST(TreeNiche, TheDefaultCatalogHasFiveTreeSpeciesAndAShrub) {
  int trees = 0, shrubs = 0;
  for (const Species& s : catalog().species) {
    if (!isTree(s)) continue;
    (s.heightM.max <= 5.0f ? shrubs : trees) += 1;
  }
  EXPECT_GE(trees, 5);
  EXPECT_GE(shrubs, 1);
}

// A forest colour near the plateau's (the conifer reference, a little brighter and yellower;
// NDVI 0.4) at five sites: which tree species wins most of 2000 draws.
std::string winnerAt(const TreeSite& site, const char* first = "conifer") {
  const Species& conifer = catalog().species[static_cast<size_t>(indexOf("conifer"))];
  std::map<int, int> wins;
  for (int k = 0; k < 2000; ++k) {
    const SpeciesChoice c = chooseTreeSpecies(catalog(), indexOf(first), GroundColour{conifer.score.reference + glm::vec3(-0.02f, 0.0f, 0.03f), kNoExg}, 0.4f, site, (float(k) + 0.5f) / 2000.0f);
    EXPECT_GE(c.species, 0);
    EXPECT_TRUE(isTree(catalog().species[static_cast<size_t>(c.species)]));
    wins[c.species] += 1;
  }
  int best = -1;
  for (const auto& [s, n] : wins)
    if (best < 0 || n > wins[best]) best = s;
  return catalog().species[static_cast<size_t>(best)].name;
}

TEST(TreeNiche, UnderTheForestsColourEachSpeciesWinsOnItsOwnGround) {
  auto site = [](float e, float slope, float relief) { return TreeSite{e, slope, relief}; };
  EXPECT_EQ(winnerAt(site(2300, 5, 0.5f)), "conifer") << "the plateau";
  EXPECT_EQ(winnerAt(site(2300, 36, 2)), "douglas fir") << "a steep slope of the plateau";
  EXPECT_EQ(winnerAt(site(2350, 3, -9)), "aspen") << "a deep hollow of the high plateau";
  EXPECT_EQ(winnerAt(site(1700, 3, 3)), "pinyon-juniper") << "a dry bench at mid height";
  EXPECT_EQ(winnerAt(site(1250, 2, -3), "broadleaf"), "broadleaf") << "the river's bottom, where the colour said broadleaf";
  EXPECT_NE(winnerAt(site(1250, 2, -3)), "broadleaf") << "a species that claims ground never takes over another's";
}

TEST(TreeNiche, ASpeciesThatClaimsNoGroundNeverWinsTheFirstChoice) {
  const int pj = indexOf("pinyon-juniper");
  ASSERT_GE(pj, 0);
  const Species& s = catalog().species[static_cast<size_t>(pj)];
  ASSERT_FALSE(s.tree.claimsGround);
  // At exactly its own reference colour, it is not even a candidate of the first choice.
  const SpeciesCandidates c = speciesCandidates(catalog(), s.score.reference, s.score.ndviReference);
  EXPECT_NE(c.first, pj);
  EXPECT_NE(c.second, pj);
  EXPECT_FALSE(passesThreshold(s, 0.0f));
  EXPECT_TRUE(passesOwnThreshold(s, 0.0f));
}

// The default catalog with `tree.niche` of its first tree species replaced by `niche`.
Result<SpeciesCatalog> withNiche(const std::string& niche) {
  std::string text(defaultSpeciesCatalogJson());
  const std::string key = "\"niche\": { \"elevation_m\": [1950, null], \"slope_deg\": [null, 30], \"relief_m\": [-6, null] }";
  const size_t at = text.find(key);
  EXPECT_NE(at, std::string::npos);
  if (at != std::string::npos) text.replace(at, key.size(), "\"niche\": " + niche);
  return parseSpeciesCatalog(text, "species.json");
}

TEST(TreeNiche, TheCatalogNamesAWrongNicheField) {
  EXPECT_TRUE(withNiche("{ \"relief_m\": [null, -1] }").ok());
  const std::pair<std::string, std::string> bad[] = {
      {"{ \"slope_deg\": [0, 95] }", "species[1].tree.niche.slope_deg[1]: must be in 0 … 90 (got 95)"},
      {"{ \"elevation_m\": [2000, 1000] }", "species[1].tree.niche.elevation_m: low must be ≤ high"},
      {"{ \"moisture\": [0, 1] }", "species[1].tree.niche.moisture: unknown key"},
      {"{ \"relief_m\": 3 }", "species[1].tree.niche.relief_m: must be [low, high]"},
      {"[1, 2]", "species[1].tree.niche: must be an object"},
  };
  for (const auto& [niche, message] : bad) {
    const auto r = withNiche(niche);
    ASSERT_FALSE(r.ok()) << niche;
    EXPECT_NE(r.error().message.find(message), std::string::npos) << r.error().message;
  }
}

}  // namespace
}  // namespace vegstream::vegetation
