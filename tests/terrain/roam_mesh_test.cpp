// The ROAM bintree over the Zion heights: wedgie thicknesses bound the surface and nest; random
// split/merge sequences keep the mesh conforming (no cracks, no T-junctions), across root tiles.

#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "core/task_runner.h"
#include "terrain/roam_mesh.h"
#include "terrain/wedgie_table.h"
#include "tests/terrain/roam_fixture.h"

namespace vegstream::terrain {
namespace {

using test::zionResident;

// Pixel-corner heights as the table sees them (mean of the four pixels around a corner).
double cornerHeight(const datasets::HeightTile& t, int i, int j) {
  const int x0 = std::max(i - 1, 0), x1 = std::min(i, t.size - 1), y0 = std::max(j - 1, 0),
            y1 = std::min(j, t.size - 1);
  return 0.25 * (double(t.at(x0, y0)) + t.at(x1, y0) + t.at(x0, y1) + t.at(x1, y1));
}

TEST(WedgieTable, ThicknessBoundsTheSurfaceAndNests) {
  auto& z = zionResident();
  const geo::TileId id = geo::tileContaining(z.meta().bounds.centre(), z.meta().maxZoom);
  const datasets::HeightTile& tile = test::ZionTiles::get().tile(id);
  const WedgieTable table(tile, z.meta().minZoom);
  // Walk the tile's bintree down to level 10 from both halves, with the dataset's diagonal.
  const bool swne = id.z > z.meta().minZoom && ((id.x + id.y) & 1) != 0;
  const GridPoint nw{0, 0}, ne{256, 0}, se{256, 256}, sw{0, 256};
  std::vector<std::pair<TriCorners, int>> stack;
  if (swne)
    stack = {{{nw, sw, ne}, 0}, {{se, ne, sw}, 0}};
  else
    stack = {{{sw, se, nw}, 0}, {{ne, nw, se}, 0}};
  uint64_t checked = 0, samples = 0;
  while (!stack.empty()) {
    auto [t, level] = stack.back();
    stack.pop_back();
    auto centroid = [](const TriCorners& c) {
      return glm::dvec2((c.apex.x + c.left.x + c.right.x) / 3.0, (c.apex.y + c.left.y + c.right.y) / 3.0);
    };
    const float e = table.thickness(level, centroid(t));
    ASSERT_GE(e, 0.0f) << "the centre tile of Zion has data everywhere";
    // Every pixel corner inside the triangle lies within its plane ± e.
    const double ha = cornerHeight(tile, int(t.apex.x), int(t.apex.y)),
                 hl = cornerHeight(tile, int(t.left.x), int(t.left.y)),
                 hr = cornerHeight(tile, int(t.right.x), int(t.right.y));
    const glm::dvec2 a(t.apex.x, t.apex.y), l(t.left.x, t.left.y), r(t.right.x, t.right.y);
    const double det = (l.x - a.x) * (r.y - a.y) - (r.x - a.x) * (l.y - a.y);
    const int step = level < 6 ? 7 : 1;
    for (int j = int(std::min({a.y, l.y, r.y})); j <= int(std::max({a.y, l.y, r.y})); j += step)
      for (int i = int(std::min({a.x, l.x, r.x})); i <= int(std::max({a.x, l.x, r.x})); i += step) {
        const double u = ((i - a.x) * (r.y - a.y) - (r.x - a.x) * (j - a.y)) / det;
        const double v = ((l.x - a.x) * (j - a.y) - (i - a.x) * (l.y - a.y)) / det;
        if (u < -1e-9 || v < -1e-9 || u + v > 1.0 + 1e-9) continue;
        const double plane = ha + u * (hl - ha) + v * (hr - ha);
        ASSERT_LE(std::abs(cornerHeight(tile, i, j) - plane), e + 1e-3) << "level " << level;
        ++samples;
      }
    ++checked;
    if (level < 10) {
      const TriCorners c0 = child(t, 0), c1 = child(t, 1);
      ASSERT_LE(table.thickness(level + 1, centroid(c0)), e);
      ASSERT_LE(table.thickness(level + 1, centroid(c1)), e);
      stack.push_back({c0, level + 1});
      stack.push_back({c1, level + 1});
    }
  }
  EXPECT_EQ(checked, 2u * ((1u << 11) - 1));
  EXPECT_GT(samples, 100000u);
}

TEST(RoamMesh, RandomSplitsAndMergesNeverCrack) {
  auto& z = zionResident();
  // Roots two zooms below the dataset's coarsest, so that diamonds cross root-tile borders (the
  // thicknesses do not matter here, only the links).
  const BintreeGrid grid(z.meta().minZoom + 2, z.meta().maxZoom);
  const geo::TileRange roots = geo::tileRangesCovering(z.meta().bounds, grid.rootZoom()).front();
  ASSERT_GT(roots.count(), 1);
  RoamMeshOptions mo;
  mo.fillHeightM = 1500.0;
  RoamMesh mesh(grid, roots, z.frame(), z.heights(), mo);
  std::mt19937 rng(1234);
  uint64_t splits = 0, merges = 0, crossings = 0;
  for (int step = 0; step < 6000; ++step) {
    const std::vector<uint32_t> leaves = mesh.leaves();
    const uint32_t t = leaves[rng() % leaves.size()];
    if (rng() % 3 != 0) {
      const TriPath before = mesh.node(t).path;
      if (mesh.split(t)) ++splits;
      if (mesh.node(t).base != kNoNode && mesh.node(mesh.node(t).base).path.rootX != before.rootX) ++crossings;
    } else {
      const uint32_t parent = mesh.node(t).parent;
      if (parent != kNoNode && mesh.isMergeable(parent)) {
        mesh.merge(parent);
        ++merges;
      }
    }
    if (step % 500 == 0) {
      ASSERT_EQ(mesh.conformityViolations(), 0u) << "after step " << step;
    }
    if (step % 1500 == 1499) {  // renumbering keeps the mesh as it is
      const uint64_t count = mesh.leafCount();
      std::set<TriPath> before;
      for (uint32_t leaf : mesh.leaves()) before.insert(mesh.node(leaf).path);
      // What the churn counters say: the pairs allocated since the last compaction, and the
      // live ones (every non-root node in the forest comes in a pair).
      uint64_t nodes = 0;
      for (std::vector<uint32_t> stack(mesh.roots()); !stack.empty();) {
        const uint32_t n = stack.back();
        stack.pop_back();
        ++nodes;
        if (!mesh.node(n).isLeaf()) stack.insert(stack.end(), {mesh.node(n).child, mesh.node(n).child + 1});
      }
      ASSERT_EQ(mesh.livePairs() * 2, nodes);
      ASSERT_GE(mesh.pairsAllocatedSinceCompact(), step == 1499 ? (nodes - mesh.roots().size()) / 2 : 500u);
      mesh.compact();
      ASSERT_EQ(mesh.pairsAllocatedSinceCompact(), 0u);
      ASSERT_EQ(mesh.livePairs() * 2, nodes);
      std::set<TriPath> after;
      for (uint32_t leaf : mesh.leaves()) after.insert(mesh.node(leaf).path);
      ASSERT_EQ(mesh.leafCount(), count);
      ASSERT_EQ(before, after);
      ASSERT_EQ(mesh.conformityViolations(), 0u) << "after compacting at step " << step;
    }
  }
  ASSERT_EQ(mesh.conformityViolations(), 0u);
  EXPECT_GT(splits, 3000u);
  EXPECT_GT(merges, 300u);
  EXPECT_GT(crossings, 0u) << "some diamonds span two root tiles";
  // Every leaf's vertices are where its path says, and shared vertices are shared by index.
  std::set<std::pair<GridPoint, uint32_t>> owners;
  for (uint32_t t : mesh.leaves()) {
    const TriCorners c = grid.corners(mesh.node(t).path);
    const TriCorners v = mesh.corners(t);
    ASSERT_EQ(c.apex, v.apex);
    ASSERT_EQ(c.left, v.left);
    ASSERT_EQ(c.right, v.right);
    for (uint32_t i : mesh.node(t).v) owners.insert({mesh.vertex(i).grid, i});
  }
  std::set<GridPoint> points;
  for (const auto& [p, i] : owners) ASSERT_TRUE(points.insert(p).second) << "two vertices at one grid point";
}

// The compaction's copy split over subtrees on a pool (roam_mesh_compaction.cpp) gives the pools
// one thread gives, and both are in depth-first order: the children of the i-th split node in
// preorder are the pair at R + 2i, and the split vertices are numbered in the order a preorder
// walk first meets them, after the root corners.
TEST(RoamMesh, CompactionOnAPoolCopiesDepthFirstLikeOneThread) {
  auto& z = zionResident();
  const BintreeGrid grid(z.meta().minZoom + 2, z.meta().maxZoom);
  const geo::TileRange roots = geo::tileRangesCovering(z.meta().bounds, grid.rootZoom()).front();
  RoamMeshOptions mo;
  mo.fillHeightM = 1500.0;
  RoamMesh one(grid, roots, z.frame(), z.heights(), mo);
  std::mt19937 rng(99);
  // Splits near one corner grow a subtree of far more than one item's 2048 leaves; merges and
  // more splits scatter the pools.
  // (The leaves are listed again every 16 steps and after a merge, which frees nodes.)
  std::vector<uint32_t> leaves;
  for (int step = 0; one.leafCount() < 30000; ++step) {
    if (step % 16 == 0 || leaves.empty()) leaves = one.leaves();
    const uint32_t t = leaves[step % 4 == 0 ? rng() % leaves.size() : rng() % (leaves.size() / 8)];
    if (!one.node(t).isLeaf()) continue;
    if (rng() % 5 != 0) {
      one.split(t);
    } else if (one.node(t).parent != kNoNode && one.isMergeable(one.node(t).parent)) {
      one.merge(one.node(t).parent);
      leaves.clear();
    }
  }
  uint32_t largestRoot = 0;
  for (uint32_t r : one.roots()) largestRoot = std::max(largestRoot, one.node(r).leafCount);
  ASSERT_GT(largestRoot, 4u * 2048u) << "a root holds several items";
  RoamMesh pooled = one;
  const RoamRenumbering a = one.compact();
  ThreadPool pool(3);
  RoamCompaction c = pooled.beginCompaction();
  pooled.buildCompaction(c, &pool);
  const RoamRenumbering b = pooled.endCompaction(std::move(c));
  ASSERT_EQ(a.nodes, b.nodes);
  ASSERT_EQ(a.vertices, b.vertices);
  ASSERT_EQ(one.nodeCapacity(), pooled.nodeCapacity());
  ASSERT_EQ(one.vertexCount(), pooled.vertexCount());
  for (uint32_t i = 0; i < one.nodeCapacity(); ++i) {
    const RoamNode &x = one.node(i), &y = pooled.node(i);
    ASSERT_TRUE(x.path == y.path && x.parent == y.parent && x.child == y.child && x.base == y.base &&
                x.left == y.left && x.right == y.right && x.mid == y.mid && x.v[0] == y.v[0] && x.v[1] == y.v[1] &&
                x.v[2] == y.v[2] && x.leafCount == y.leafCount && x.drawnChunk == kNoNode && y.drawnChunk == kNoNode)
        << "node " << i;
  }
  for (uint32_t i = 0; i < one.vertexCount(); ++i) {
    ASSERT_EQ(one.vertex(i).grid, pooled.vertex(i).grid) << "vertex " << i;
    ASSERT_EQ(one.vertex(i).at, pooled.vertex(i).at) << "vertex " << i;
  }
  // Depth-first order, walked here.
  const auto rootCount = static_cast<uint32_t>(one.roots().size());
  uint32_t split = 0, nextVertex = 0;
  std::set<uint32_t> met;
  for (uint32_t r : one.roots())
    for (uint32_t v : one.node(r).v)
      if (met.insert(v).second) ++nextVertex;  // the root corners come first
  ASSERT_EQ(met.size(), nextVertex);
  ASSERT_EQ(*met.rbegin() + 1, nextVertex);
  std::vector<uint32_t> stack(one.roots().rbegin(), one.roots().rend());
  while (!stack.empty()) {
    const uint32_t t = stack.back();
    stack.pop_back();
    const RoamNode& n = one.node(t);
    if (n.isLeaf()) continue;
    ASSERT_EQ(n.child, rootCount + 2 * split++);
    if (met.insert(n.mid).second) {
      ASSERT_EQ(n.mid, nextVertex++);
    }
    stack.push_back(n.child + 1);
    stack.push_back(n.child);
  }
  EXPECT_EQ(split + split + rootCount, one.nodeCapacity());
  EXPECT_EQ(nextVertex, one.vertexCount());
  EXPECT_EQ(one.conformityViolations(), 0u);
  EXPECT_EQ(pooled.conformityViolations(), 0u);
}

TEST(RoamMesh, VerticesSampleTheHeightsAndSitInTheFrame) {
  auto& z = zionResident();
  RoamMesh mesh(z.grid(), z.roots(), z.frame(), z.heights());
  std::mt19937 rng(7);
  for (int i = 0; i < 3000; ++i) {
    const std::vector<uint32_t> leaves = mesh.leaves();
    mesh.split(leaves[rng() % leaves.size()]);
  }
  int checked = 0;
  for (uint32_t t : mesh.leaves()) {
    for (uint32_t vi : mesh.node(t).v) {
      const RoamVertex& v = mesh.vertex(vi);
      if (!(v.heightM == v.heightM)) continue;
      const glm::dvec2 ll = geo::tileXYToLonLat(z.grid().tileXY(v.grid, z.grid().gridZoom()), z.grid().gridZoom());
      const HeightSample s = z.heights().sampleLonLat(ll.y, ll.x);
      ASSERT_NEAR(v.heightM, s.heightM, 1e-6);
      const glm::dvec3 p = z.frame().toLocal({ll.y, ll.x, v.heightM});
      ASSERT_LT(glm::length(v.position(v.heightM) - p), 1e-3);
      ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace vegstream::terrain
