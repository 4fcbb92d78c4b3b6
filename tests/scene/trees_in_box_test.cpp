// scene::treesInBox (scene/trees_in_box.h, issue 20) on the Zion sample with NDVI: the same box
// gives the same trees, a box's trees are exactly the larger box's trees that lie in it (view
// and box independence: core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2), the Kolob
// plateau is forest (its tree density is printed), and mistakes are errors naming the box.

#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include <gtest/gtest.h>

#include "scene/trees_in_box.h"
#include "tests/scene/zion_trees_fixture.h"

namespace vegstream::scene {
namespace {

const vegetation::SpeciesCatalog& catalog() { return vegetation::defaultSpeciesCatalog(); }

auto tie(const BoxTree& t) {
  return std::make_tuple(t.at.latDeg, t.at.lonDeg, t.at.heightM, t.species, t.seed, t.heightM, t.crownM, t.sPrime);
}
bool inBox(const BoxTree& t, const geo::GeoBounds& b) {
  return t.at.lonDeg >= b.westDeg && t.at.lonDeg < b.eastDeg && t.at.latDeg >= b.southDeg && t.at.latDeg < b.northDeg;
}
// The box's ground area, hectares (the ellipsoid's metres per degree at its centre).
double hectares(const geo::GeoBounds& b) {
  const double lat = 0.5 * (b.southDeg + b.northDeg) * M_PI / 180.0;
  const double mLat = 111132.92 - 559.82 * std::cos(2 * lat), mLon = 111412.84 * std::cos(lat);
  return (b.eastDeg - b.westDeg) * mLon * (b.northDeg - b.southDeg) * mLat / 1e4;
}

class TreesInBoxTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto dir = testing::zionWithNdvi();
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    dataset_ = dir->string();
  }
  std::string dataset_;
};

TEST_F(TreesInBoxTest, TheSameBoxTwiceAndASubBoxGiveTheSameTrees) {
  const geo::GeoBounds big{-113.080, 37.450, -113.070, 37.458}, small{-113.0775, 37.4515, -113.0712, 37.4561};
  const auto a = treesInBox(dataset_, big, catalog(), {}), b = treesInBox(dataset_, big, catalog(), {});
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_TRUE(b.ok()) << b.error().message;
  ASSERT_GT(a->trees.size(), 300u);
  ASSERT_EQ(a->trees.size(), b->trees.size());
  for (size_t i = 0; i < a->trees.size(); ++i) ASSERT_EQ(tie(a->trees[i]), tie(b->trees[i])) << i;
  for (const BoxTree& t : a->trees) {
    ASSERT_TRUE(inBox(t, big));
    ASSERT_TRUE(vegetation::isTree(catalog().species[t.species]));
  }
  const auto s = treesInBox(dataset_, small, catalog(), {});
  ASSERT_TRUE(s.ok()) << s.error().message;
  std::vector<BoxTree> expected;
  for (const BoxTree& t : a->trees)
    if (inBox(t, small)) expected.push_back(t);
  std::printf("[ figures  ] big box %zu trees, small box %zu, of which the big box has %zu\n", a->trees.size(),
              s->trees.size(), expected.size());
  EXPECT_GT(expected.size(), 100u);
  ASSERT_EQ(s->trees.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) ASSERT_EQ(tie(s->trees[i]), tie(expected[i])) << i;
}

TEST_F(TreesInBoxTest, TheKolobPlateauIsForest) {
  const geo::GeoBounds kolob{-113.10, 37.44, -113.05, 37.47};
  const auto r = treesInBox(dataset_, kolob, catalog(), {});
  ASSERT_TRUE(r.ok()) << r.error().message;
  std::map<std::string, size_t> perSpecies;
  for (const BoxTree& t : r->trees) ++perSpecies[catalog().species[t.species].name];
  const double ha = hectares(kolob), density = double(r->trees.size()) / ha;
  std::printf("[ figures  ] Kolob plateau %.0f ha: %zu trees, %.1f per ha (cells of %.2f m, ground zoom %d)",
              ha, r->trees.size(), density, r->cellM, r->groundZoom);
  for (const auto& [name, n] : perSpecies) std::printf(", %s %.1f/ha", name.c_str(), double(n) / ha);
  std::printf("\n");
  EXPECT_GT(density, 30.0);
  EXPECT_GT(perSpecies["conifer"], perSpecies["broadleaf"]) << "a conifer plateau";
}

TEST_F(TreesInBoxTest, MistakesNameTheBoxOrTheLimitAndNoTreeSpeciesGrowsNone) {
  const geo::GeoBounds outside{-112.0, 37.44, -111.9, 37.47};
  TreesInBoxOptions o;
  o.boxName = "--bbox X";
  o.maxTreesName = "--max-trees";
  const auto out = treesInBox(dataset_, outside, catalog(), o);
  ASSERT_FALSE(out.ok());
  EXPECT_EQ(out.error().kind, ErrorKind::InvalidInput);
  EXPECT_EQ(out.error().message.rfind("--bbox X: not inside the dataset's bounds", 0), 0u) << out.error().message;
  o.maxTrees = 10;
  const auto many = treesInBox(dataset_, {-113.080, 37.450, -113.070, 37.458}, catalog(), o);
  ASSERT_FALSE(many.ok());
  EXPECT_NE(many.error().message.find("more than --max-trees 10"), std::string::npos) << many.error().message;
  const auto missing = treesInBox(dataset_ + "/no-such", {-113.080, 37.450, -113.070, 37.458}, catalog(), {});
  EXPECT_FALSE(missing.ok());
  // A catalog without trees: none, and no error.
  vegetation::SpeciesCatalog grassOnly;
  for (const vegetation::Species& sp : catalog().species)
    if (!vegetation::isTree(sp)) grassOnly.species.push_back(sp);
  const auto none = treesInBox(dataset_, {-113.080, 37.450, -113.070, 37.458}, grassOnly, {});
  ASSERT_TRUE(none.ok()) << none.error().message;
  EXPECT_TRUE(none->trees.empty());
}

}  // namespace
}  // namespace vegstream::scene
