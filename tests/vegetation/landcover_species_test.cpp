// vegetation/landcover_species.h (issue 41, item 2): the built-in kind → species default from the
// species' kinds, the catalog's "landcover" table (read, and refused in one line naming the field
// where it names a species the catalog lacks), and the species choice (core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16–18) restricted to the allowed species.

#include "vegetation/landcover_species.h"

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "vegetation/philox.h"
#include "vegetation/species_catalog.h"
#include "vegetation/species_choice.h"

namespace vegstream::vegetation {
namespace {

using nlohmann::json;

int indexOf(const SpeciesCatalog& c, const std::string& name) {
  for (size_t i = 0; i < c.species.size(); ++i)
    if (c.species[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no species " << name;
  return 0;
}

SpeciesMask bit(const SpeciesCatalog& c, const std::string& name) { return SpeciesMask{1} << indexOf(c, name); }

SpeciesMask allowed(const SpeciesCatalog& c, LandcoverKind k) { return allowedSpecies(c, k); }

TEST(LandcoverSpecies, TheDefaultFollowsTheSpeciesKinds) {
  const SpeciesCatalog& c = defaultSpeciesCatalog();
  ASSERT_FALSE(c.landcover) << "the shipped catalog relies on the built-in default";
  const SpeciesMask bare = bit(c, "pale sandstone") | bit(c, "grey rock") | bit(c, "sand");
  SpeciesMask trees = 0;  // every tree species, the ones that only share the ground (tree_niche.h) too
  for (size_t i = 0; i < c.species.size(); ++i)
    if (isTree(c.species[i])) trees |= SpeciesMask{1} << i;
  EXPECT_EQ(trees & (bit(c, "conifer") | bit(c, "broadleaf") | bit(c, "aspen")), bit(c, "conifer") | bit(c, "broadleaf") | bit(c, "aspen"));
  const SpeciesMask herbs = bit(c, "grass") | bit(c, "dry tufts");
  EXPECT_EQ(allowed(c, LandcoverKind::Tree), trees | bare);
  EXPECT_EQ(allowed(c, LandcoverKind::Grass), herbs | bare);
  EXPECT_EQ(allowed(c, LandcoverKind::Crop), herbs | bare);
  EXPECT_EQ(allowed(c, LandcoverKind::Wetland), herbs | bare);
  EXPECT_EQ(allowed(c, LandcoverKind::Shrub), herbs | bit(c, "red gravel") | bare);
  EXPECT_EQ(allowed(c, LandcoverKind::Bare), bit(c, "red gravel") | bare);
  EXPECT_EQ(allowed(c, LandcoverKind::Built), 0u);
  EXPECT_EQ(allowed(c, LandcoverKind::Water), 0u);
  EXPECT_EQ(allowed(c, LandcoverKind::Snow), 0u);
}

json withTable(json table) {
  json doc = json::parse(defaultSpeciesCatalogJson());
  doc["landcover"] = std::move(table);
  return doc;
}

TEST(LandcoverSpecies, TheCatalogTableReplacesTheKindsItNames) {
  auto r = parseSpeciesCatalog(withTable({{"tree", {"broadleaf"}}, {"built", {"grass"}}, {"grass", json::array()}})
                                   .dump(),
                               "species.json");
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->landcover);
  EXPECT_EQ(allowed(*r, LandcoverKind::Tree), bit(*r, "broadleaf"));
  EXPECT_EQ(allowed(*r, LandcoverKind::Built), bit(*r, "grass"));
  EXPECT_EQ(allowed(*r, LandcoverKind::Grass), 0u);
  // Kinds it leaves out keep the default.
  EXPECT_EQ(allowed(*r, LandcoverKind::Bare), allowed(defaultSpeciesCatalog(), LandcoverKind::Bare));
}

TEST(LandcoverSpecies, ABadTableIsRefusedInOneLineNamingTheField) {
  struct Case {
    json table;
    std::string message;
  };
  const Case cases[] = {
      {{{"tree", {"conifer", "oak"}}}, "species.json: landcover.tree[1]: no species named \"oak\" in the catalog"},
      {{{"forest", {"conifer"}}}, "species.json: landcover.forest: unknown landcover kind"},
      {{{"tree", "conifer"}}, "species.json: landcover.tree: must be an array of species names"},
      {{{"tree", {"conifer", "conifer"}}}, "species.json: landcover.tree[1]: \"conifer\" is named twice"},
      {{{"tree", {3}}}, "species.json: landcover.tree[0]: must be a species name"},
      {json::array(), "species.json: landcover: must be an object"},
  };
  for (const Case& c : cases) {
    auto r = parseSpeciesCatalog(withTable(c.table).dump(), "species.json");
    ASSERT_FALSE(r.ok()) << c.table.dump();
    EXPECT_EQ(r.error().message.rfind(c.message, 0), 0u) << r.error().message;
    EXPECT_EQ(r.error().message.find('\n'), std::string::npos);
  }
}

// Over many base colours and draws: with every species allowed the choice is today's; with a
// class's mask the winner is always one the class allows, and only allowed species compete.
TEST(LandcoverSpecies, TheChoiceStaysWithinTheAllowedSpecies) {
  const SpeciesCatalog& c = defaultSpeciesCatalog();
  const SpeciesMask tree = allowed(c, LandcoverKind::Tree), grass = allowed(c, LandcoverKind::Grass);
  int trees = 0, herbs = 0, changed = 0;
  for (uint32_t i = 0; i < 4000; ++i) {
    const Philox2x32Out r = philox(i, 7u, 0x1c0u);
    const Philox2x32Out s = philox(i, 8u, 0x1c0u);
    const glm::vec3 hsv(u01(r.x), u01(r.y), u01(s.x) * 0.6f);
    const float z = u01(s.y);
    const SpeciesChoice all = chooseSpecies(c, hsv, z);
    const SpeciesChoice unmasked = chooseSpecies(c, hsv, z, kNoNdvi, kNoExg, kAllSpecies);
    EXPECT_EQ(all.species, unmasked.species);
    EXPECT_EQ(all.sPrime, unmasked.sPrime);
    const SpeciesChoice inTree = chooseSpecies(c, hsv, z, kNoNdvi, kNoExg, tree);
    const SpeciesChoice inGrass = chooseSpecies(c, hsv, z, kNoNdvi, kNoExg, grass);
    const SpeciesChoice inBuilt = chooseSpecies(c, hsv, z, kNoNdvi, kNoExg, allowed(c, LandcoverKind::Built));
    EXPECT_EQ(inBuilt.species, -1);
    if (inTree.species >= 0) {
      EXPECT_TRUE(isTree(c.species[size_t(inTree.species)])) << c.species[size_t(inTree.species)].name;
      ++trees;
    }
    if (inGrass.species >= 0) {
      const RendererKind k = c.species[size_t(inGrass.species)].kind;
      EXPECT_TRUE(k == RendererKind::Grass || k == RendererKind::Flowers) << c.species[size_t(inGrass.species)].name;
      ++herbs;
    }
    const SpeciesCandidates cand = speciesCandidates(c, hsv, kNoNdvi, kNoExg, tree);
    if (cand.first >= 0) {
      EXPECT_NE(tree & (SpeciesMask{1} << cand.first), 0u);
    }
    if (cand.second >= 0) {
      EXPECT_NE(tree & (SpeciesMask{1} << cand.second), 0u);
    }
    changed += inGrass.species != all.species;
  }
  // Both classes grow (colour still picks within them), and the mask does change choices.
  EXPECT_GT(trees, 400);
  EXPECT_GT(herbs, 400);
  EXPECT_GT(changed, 400);
}

}  // namespace
}  // namespace vegstream::vegetation
