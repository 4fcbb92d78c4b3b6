// The trees around the camera (scene/tree_field.h, issue 20): tiles placed once and drawn from
// pages of the renderer's pool, nearest first; the same trees whichever camera placed a tile; the
// budget binding on the far tiles, and saying so.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

#include <gtest/gtest.h>

#include "scene/tree_field.h"
#include "vegetation/colour_score.h"

namespace vegstream::scene {
namespace {

using vegetation::TreeGroundAt;
using vegetation::TreeGroundSample;

const vegetation::SpeciesCatalog& catalog() { return vegetation::defaultSpeciesCatalog(); }

// Conifer forest in bands with meadows between, on gently varying ground.
TreeGroundAt forestBands() {
  const auto of = [](const char* name) {
    for (const vegetation::Species& s : catalog().species)
      if (s.name == name) {
        const glm::vec3 srgb = vegetation::srgbFromHsv(s.score.reference);
        return TreeGroundSample{true,
                                {vegetation::srgbDecode(srgb.r), vegetation::srgbDecode(srgb.g),
                                 vegetation::srgbDecode(srgb.b)},
                                s.score.ndviReference,
                                0.0};
      }
    ADD_FAILURE() << name;
    return TreeGroundSample{};
  };
  const TreeGroundSample forest = of("conifer"), meadow = of("grass");
  return [=](double x, double y) {
    TreeGroundSample g = std::fmod(std::abs(x + 3000.0), 400.0) < 250.0 ? forest : meadow;
    g.heightM = 10.0 * std::sin(y / 300.0);
    return g;
  };
}

std::vector<uint32_t> firstModels() {
  std::vector<uint32_t> first(catalog().species.size(), UINT32_MAX);
  uint32_t next = 0;
  for (size_t s = 0; s < first.size(); ++s)
    if (vegetation::isTree(catalog().species[s])) first[s] = next, next += 3;
  return first;
}

// Every tree a request draws, as (x, y, seed), from its uploads over the frames so far.
struct PoolMirror {
  std::map<uint32_t, std::vector<render::TreeInstanceGpu>> pages;
  void apply(const render::TreeRequest& r) {
    for (const render::TreePageUpload& u : r.uploads) pages[u.page].assign(u.instances, u.instances + u.count);
  }
  std::set<std::tuple<float, float, uint32_t>> drawn(const render::TreeRequest& r) const {
    std::set<std::tuple<float, float, uint32_t>> out;
    for (uint32_t p = 0; p < r.pageCounts.size(); ++p) {
      if (r.pageCounts[p] == 0) continue;
      const auto& page = pages.at(p);
      EXPECT_EQ(page.size(), r.pageCounts[p]);
      for (const render::TreeInstanceGpu& t : page) out.insert({t.position[0], t.position[1], t.seed});
    }
    return out;
  }
};

TreeFieldOptions smallField() {
  TreeFieldOptions o;
  o.lod.horizonM = 600.0f;
  return o;
}

TEST(TreeField, SettledFramesDrawEveryTreeWithinTheHorizonAndTheSameTreesFromAnyCamera) {
  TreeField a(catalog(), forestBands(), smallField(), firstModels(), 3, 4096);
  PoolMirror pool;
  const render::TreeRequest& r = a.prepare({0.0, 0.0, 50.0}, /*settled=*/true);
  pool.apply(r);
  const auto near = pool.drawn(r);
  const TreeFieldFigures& f = a.figures();
  EXPECT_FALSE(f.budgetBound);
  EXPECT_GT(f.tilesDrawn, 4u);
  EXPECT_LE(f.tilesDrawn, f.tilesWanted);  // tiles without trees (meadow) take no pages
  EXPECT_GT(near.size(), 20000u);
  EXPECT_EQ(near.size(), f.treesDrawn);
  // A second field placed from a camera 400 m east: the trees both draw are the same trees.
  TreeField b(catalog(), forestBands(), smallField(), firstModels(), 3, 4096);
  PoolMirror poolB;
  const render::TreeRequest& rb = b.prepare({400.0, 0.0, 50.0}, true);
  poolB.apply(rb);
  const auto far = poolB.drawn(rb);
  size_t shared = 0;
  for (const auto& t : near) shared += far.count(t);
  // Trees in the overlap of the two discs (of whole tiles) are in both; none is moved or changed.
  std::set<std::pair<int, int>> nearTiles, farTiles;
  const double side = a.grid().cellM * smallField().tileCells;
  for (const auto& [x, y, s] : near) nearTiles.insert({int(std::floor(x / side)), int(std::floor(y / side))});
  for (const auto& [x, y, s] : far) farTiles.insert({int(std::floor(x / side)), int(std::floor(y / side))});
  size_t expectedShared = 0;
  for (const auto& t : near)
    if (farTiles.count({int(std::floor(std::get<0>(t) / side)), int(std::floor(std::get<1>(t) / side))}))
      ++expectedShared;
  std::printf("%zu trees from the first camera, %zu from the second, %zu in tiles both draw, %zu identical\n",
              near.size(), far.size(), expectedShared, shared);
  EXPECT_GT(expectedShared, 5000u);
  EXPECT_EQ(shared, expectedShared);
}

TEST(TreeField, MovingFreesTheTilesBehindAndRealtimePlacesAFewPerFrame) {
  TreeFieldOptions o = smallField();
  o.placementsPerFrame = 2;
  TreeField f(catalog(), forestBands(), o, firstModels(), 3, 4096);
  (void)f.prepare({0.0, 0.0, 50.0}, false);
  EXPECT_EQ(f.figures().placed, 2u);
  EXPECT_LT(f.figures().tilesDrawn, f.figures().tilesWanted);
  for (int i = 0; i < 200; ++i) (void)f.prepare({0.0, 0.0, 50.0}, false);
  EXPECT_EQ(f.figures().placed, 0u);  // all placed
  const uint32_t pagesHere = f.figures().pagesUsed;
  // 3 km east: nothing of the old disc is wanted; its pages came back and serve the new tiles.
  (void)f.prepare({3000.0, 0.0, 50.0}, true);
  EXPECT_LE(f.figures().pagesUsed, 4096u);
  EXPECT_NEAR(double(f.figures().pagesUsed), double(pagesHere), 0.5 * pagesHere);
  EXPECT_FALSE(f.figures().budgetBound);
}

TEST(TreeField, WhenTheBudgetBindsTheNearestTilesKeepTheirTreesAndTheFiguresSaySo) {
  const uint32_t capacity = 40;  // pages of 256 trees: far fewer than the disc holds
  TreeField f(catalog(), forestBands(), smallField(), firstModels(), 3, capacity);
  PoolMirror pool;
  const render::TreeRequest& r = f.prepare({0.0, 0.0, 50.0}, true);
  pool.apply(r);
  EXPECT_TRUE(f.figures().budgetBound);
  EXPECT_LE(f.figures().pagesUsed, capacity);
  EXPECT_GT(f.figures().pagesUsed, capacity - 8);
  // The drawn tiles are the nearest: every tile with trees that is not drawn is at least as far
  // as every drawn one (distances from the camera to the tiles' squares; all tiles from an
  // unbounded field).
  TreeField all(catalog(), forestBands(), smallField(), firstModels(), 3, 4096);
  PoolMirror allPool;
  const render::TreeRequest& ra = all.prepare({0.0, 0.0, 50.0}, true);
  allPool.apply(ra);
  const double side = f.grid().cellM * smallField().tileCells;
  const auto tileDistance = [&](float x, float y) {
    const double tx = std::floor(x / side), ty = std::floor(y / side);
    const double dx = std::max({tx * side, 0.0, -(tx + 1) * side}), dy = std::max({ty * side, 0.0, -(ty + 1) * side});
    return std::hypot(dx, dy);
  };
  const auto drawn = pool.drawn(r);
  ASSERT_FALSE(drawn.empty());
  double farthestDrawn = 0.0, nearestLeft = 1e9;
  for (const auto& [x, y, s] : drawn) farthestDrawn = std::max(farthestDrawn, tileDistance(x, y));
  for (const auto& t : allPool.drawn(ra))
    if (!drawn.count(t)) nearestLeft = std::min(nearestLeft, tileDistance(std::get<0>(t), std::get<1>(t)));
  std::printf("%zu of %zu trees drawn in %u pages; drawn tiles up to %.0f m away, the nearest left out at %.0f m\n",
              drawn.size(), allPool.drawn(ra).size(), f.figures().pagesUsed, farthestDrawn, nearestLeft);
  EXPECT_LT(drawn.size(), allPool.drawn(ra).size());
  EXPECT_LE(farthestDrawn, nearestLeft);
}

}  // namespace
}  // namespace vegstream::scene
