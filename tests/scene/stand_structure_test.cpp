// Stands that grow like stands (issue 41 item 4) on the Zion sample with NDVI: over 9 ha of the
// Kolob plateau's forest, the trees of scene::treesInBox are no lattice — Clark–Evans R (Clark &
// Evans 1954, Donnelly's edge correction: vegetation/stand_statistics.h) within 0.85–1.35, where
// natural stands are about 0.9–1.3 — and their heights vary (CV ≥ 0.25 for every species with
// enough trees). The same 9 ha asked as one box and as four quarters give the same trees (view
// independence, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §2.2).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "scene/trees_in_box.h"
#include "tests/scene/zion_trees_fixture.h"
#include "vegetation/stand_statistics.h"

namespace vegstream::scene {
namespace {

const vegetation::SpeciesCatalog& catalog() { return vegetation::defaultSpeciesCatalog(); }

// 300 m × 300 m of the Kolob plateau's forest (around 37.4603 N, 113.0254 W: the densest 9 ha window of the plateau, about 130 trees per ha).
constexpr double kLat = 37.4603, kLon = -113.0254;
double metresPerDegLat() { return 111132.92 - 559.82 * std::cos(2 * kLat * M_PI / 180.0); }
double metresPerDegLon() { return 111412.84 * std::cos(kLat * M_PI / 180.0); }
geo::GeoBounds nineHectares() {
  const double dLat = 150.0 / metresPerDegLat(), dLon = 150.0 / metresPerDegLon();
  return {kLon - dLon, kLat - dLat, kLon + dLon, kLat + dLat};
}

auto tie(const BoxTree& t) {
  return std::make_tuple(t.at.latDeg, t.at.lonDeg, t.at.heightM, t.species, t.seed, t.heightM, t.crownM, t.sPrime);
}

class StandStructureTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto dir = testing::zionWithNdvi();
    ASSERT_TRUE(dir.ok()) << dir.error().message;
    dataset_ = dir->string();
  }
  std::string dataset_;
};

TEST_F(StandStructureTest, NineHectaresOfKolobForestAreAStandNotALattice) {
  const geo::GeoBounds box = nineHectares();
  const auto r = treesInBox(dataset_, box, catalog(), {});
  ASSERT_TRUE(r.ok()) << r.error().message;
  std::vector<glm::dvec2> at;
  std::map<uint32_t, std::vector<double>> heights;
  std::vector<double> crowns, all;
  for (const BoxTree& t : r->trees) {
    at.push_back({(t.at.lonDeg - box.westDeg) * metresPerDegLon(), (t.at.latDeg - box.southDeg) * metresPerDegLat()});
    heights[t.species].push_back(t.heightM);
    all.push_back(t.heightM);
  }
  const double w = (box.eastDeg - box.westDeg) * metresPerDegLon(), h = (box.northDeg - box.southDeg) * metresPerDegLat();
  const vegetation::ClarkEvans ce = vegetation::clarkEvans(at, 0.0, 0.0, w, h);
  std::printf("[ figures  ] Kolob %.0f m x %.0f m: %zu trees (%.1f per ha), Clark-Evans R %.3f (mean nearest %.2f m, "
              "expected %.2f m), height CV %.3f over all",
              w, h, r->trees.size(), double(r->trees.size()) / (w * h / 1e4), ce.r, ce.meanNearestM, ce.expectedM,
              vegetation::coefficientOfVariation(all));
  for (const auto& [s, v] : heights)
    std::printf(", %s %zu trees CV %.3f", catalog().species[s].name.c_str(), v.size(),
                vegetation::coefficientOfVariation(v));
  std::printf("\n");
  ASSERT_GT(r->trees.size(), 400u) << "the box is forest";
  EXPECT_GE(ce.r, 0.85);
  EXPECT_LE(ce.r, 1.35);
  for (const auto& [s, v] : heights) {
    if (v.size() < 30) continue;
    EXPECT_GE(vegetation::coefficientOfVariation(v), 0.25) << catalog().species[s].name;
  }
}

TEST_F(StandStructureTest, TheSameTreesTwiceAndAsFourQuarters) {
  const geo::GeoBounds box = nineHectares();
  const auto a = treesInBox(dataset_, box, catalog(), {}), b = treesInBox(dataset_, box, catalog(), {});
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_TRUE(b.ok()) << b.error().message;
  ASSERT_GT(a->trees.size(), 400u);
  ASSERT_EQ(a->trees.size(), b->trees.size());
  for (size_t i = 0; i < a->trees.size(); ++i) ASSERT_EQ(tie(a->trees[i]), tie(b->trees[i])) << i;
  const double midLon = 0.5 * (box.westDeg + box.eastDeg), midLat = 0.5 * (box.southDeg + box.northDeg);
  std::vector<BoxTree> quarters;
  for (const geo::GeoBounds& q : {geo::GeoBounds{box.westDeg, box.southDeg, midLon, midLat},
                                  geo::GeoBounds{midLon, box.southDeg, box.eastDeg, midLat},
                                  geo::GeoBounds{box.westDeg, midLat, midLon, box.northDeg},
                                  geo::GeoBounds{midLon, midLat, box.eastDeg, box.northDeg}}) {
    const auto part = treesInBox(dataset_, q, catalog(), {});
    ASSERT_TRUE(part.ok()) << part.error().message;
    quarters.insert(quarters.end(), part->trees.begin(), part->trees.end());
  }
  auto order = [](const BoxTree& x, const BoxTree& y) { return tie(x) < tie(y); };
  std::vector<BoxTree> whole = a->trees;
  std::sort(whole.begin(), whole.end(), order);
  std::sort(quarters.begin(), quarters.end(), order);
  std::printf("[ figures  ] one box %zu trees, four quarters %zu\n", whole.size(), quarters.size());
  ASSERT_EQ(quarters.size(), whole.size());
  for (size_t i = 0; i < whole.size(); ++i) ASSERT_EQ(tie(quarters[i]), tie(whole[i])) << i;
}

}  // namespace
}  // namespace vegstream::scene
