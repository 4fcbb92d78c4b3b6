// Chunked-LOD tile selection over the Zion sample's bounds and height range (imported once per
// process, zion_tiles.h), for a dataset of max zoom 14 as the Zion import test makes: nodes go
// down to zoom 14 + kLevelsBeyondData = 17, one mesh quad per data pixel.

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "terrain/tile_selection.h"
#include "tests/terrain/zion_tiles.h"

namespace vegstream::terrain {
namespace {

constexpr double kFovY = 60.0 * 3.14159265358979323846 / 180.0;

SelectionDataset zionDataset() {
  const datasets::DatasetMeta& m = test::ZionTiles::get().meta();
  return {m.bounds, m.minZoom, 14 + kLevelsBeyondData, m.minHeightM, m.maxHeightM};
}

geo::LocalFrame zionFrame() {
  const SelectionDataset d = zionDataset();
  return geo::frameAtCentre(d.bounds, 0.5 * (d.minHeightM + d.maxHeightM));
}

// A 1920 × 1080 perspective camera at `eye` looking along `dir`, Vulkan depth [0, 1].
SelectionView camera(glm::dvec3 eye, glm::dvec3 dir, glm::dvec3 up = {0, 0, 1}) {
  const glm::dmat4 view = glm::lookAt(eye, eye + dir, up);
  const glm::dmat4 proj = glm::perspective(kFovY, 1920.0 / 1080.0, 1.0, 1e6);
  return {eye, proj * view, 1080.0, kFovY};
}

SelectionView topDown(const geo::LocalFrame& frame, double lonDeg, double latDeg, double heightM) {
  return camera(frame.toLocal({latDeg, lonDeg, heightM}), {0, 0, -1}, {0, 1, 0});
}

bool isAncestor(const geo::TileId& a, const geo::TileId& d) {
  if (a.z >= d.z) return false;
  const int s = d.z - a.z;
  return (d.x >> s) == a.x && (d.y >> s) == a.y;
}

void expectNoOverlap(const Selection& s) {
  for (const SelectedNode& a : s.nodes)
    for (const SelectedNode& b : s.nodes) {
      ASSERT_FALSE(isAncestor(a.id, b.id)) << geo::toString(a.id) << " is an ancestor of " << geo::toString(b.id);
      if (&a != &b) {
        ASSERT_NE(a.id, b.id);
      }
    }
}

void expectErrorBound(const Selection& s, const SelectionDataset& d, const SelectionOptions& o) {
  double worst = 0.0;
  for (const SelectedNode& n : s.nodes) {
    worst = std::max(worst, n.projectedErrorPx);
    if (n.id.z < d.maxZoom && !s.budgetLimited) {
      EXPECT_LE(n.projectedErrorPx, o.maxErrorPx) << geo::toString(n.id);
    }
  }
  EXPECT_EQ(s.achievedErrorPx, worst);
  EXPECT_LE(s.nodes.size(), static_cast<size_t>(o.maxNodes));
}

TEST(TileSelection, TopDownLeavesCoverTheDatasetWithoutOverlap) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  const glm::dvec2 c = d.bounds.centre();
  const SelectionOptions o{2.0, 4096};
  const Selection s = selectTiles(topDown(frame, c.x, c.y, 80'000.0), d, frame, o);
  ASSERT_GT(s.nodes.size(), 20u);
  EXPECT_FALSE(s.budgetLimited);
  expectNoOverlap(s);
  expectErrorBound(s, d, o);
  // Areas in zoom-14 tile units (Web Mercator is affine in them): Σ area(leaf ∩ bounds) equals
  // area(bounds) exactly when the non-overlapping leaves cover the bounds.
  const int Z = 20;
  const glm::dvec2 nw = geo::lonLatToTileXY({d.bounds.westDeg, d.bounds.northDeg}, Z);
  const glm::dvec2 se = geo::lonLatToTileXY({d.bounds.eastDeg, d.bounds.southDeg}, Z);
  const double boundsArea = (se.x - nw.x) * (se.y - nw.y);
  double sum = 0.0;
  for (const SelectedNode& n : s.nodes) {
    const double k = std::ldexp(1.0, Z - n.id.z);
    const double w = std::min(se.x, (n.id.x + 1) * k) - std::max(nw.x, n.id.x * k);
    const double h = std::min(se.y, (n.id.y + 1) * k) - std::max(nw.y, n.id.y * k);
    ASSERT_GT(w, 0.0);
    ASSERT_GT(h, 0.0);
    sum += w * h;
  }
  EXPECT_NEAR(sum / boundsArea, 1.0, 1e-9) << s.nodes.size() << " leaves";
}

TEST(TileSelection, LowCameraMeetsTheBoundOrTheBudget) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  // 150 m above the highest point, near the south-west corner, looking north-east and down 10°.
  const glm::dvec3 eye = frame.toLocal({d.bounds.southDeg + 0.05, d.bounds.westDeg + 0.05, d.maxHeightM + 150.0});
  const glm::dvec3 dir = glm::normalize(glm::dvec3(1.0, 1.0, -0.25));
  const SelectionView v = camera(eye, dir);

  const SelectionOptions wide{2.0, 100'000};
  const Selection full = selectTiles(v, d, frame, wide);
  EXPECT_FALSE(full.budgetLimited);
  expectNoOverlap(full);
  expectErrorBound(full, d, wide);
  EXPECT_GT(full.achievedErrorPx, 2.0) << "the finest nodes under a low camera exceed the bound";
  ASSERT_GT(full.nodes.size(), 256u) << "the budgets below must bite";
  for (const int budget : {16, 64, 256}) {
    const SelectionOptions o{2.0, budget};
    const Selection s = selectTiles(v, d, frame, o);
    SCOPED_TRACE(budget);
    expectNoOverlap(s);
    expectErrorBound(s, d, o);
    if (full.nodes.size() > static_cast<size_t>(budget)) {
      EXPECT_TRUE(s.budgetLimited);
      // Worst-first refinement: at most 3 short of the budget (one more refinement adds ≤ 3).
      EXPECT_GE(s.nodes.size() + 3, static_cast<size_t>(budget));
      // The budget only withholds refinement: every leaf is the same as, or an ancestor of,
      // leaves of the unlimited selection, and some leaf is still refinable.
      bool refinable = false;
      for (const SelectedNode& n : s.nodes) {
        bool found = false;
        for (const SelectedNode& f : full.nodes) found = found || f.id == n.id || isAncestor(n.id, f.id);
        EXPECT_TRUE(found) << geo::toString(n.id);
        refinable = refinable || (n.projectedErrorPx > o.maxErrorPx && n.id.z < d.maxZoom);
      }
      EXPECT_TRUE(refinable);
    }
  }
}

TEST(TileSelection, NodesBehindTheCameraAreCulled) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  // At the frame's meridian (x = 0 in ENU), looking due east, level: everything west is behind.
  const glm::dvec3 eye = frame.toLocal({frame.origin().latDeg, frame.origin().lonDeg, d.maxHeightM + 300.0});
  ASSERT_NEAR(eye.x, 0.0, 1e-6);
  const SelectionOptions o{2.0, 100'000};
  const Selection east = selectTiles(camera(eye, {1, 0, 0}), d, frame, o);
  ASSERT_FALSE(east.nodes.empty());
  int behind = 0;
  for (const SelectedNode& n : east.nodes) {
    const geo::GeoBounds b = geo::tileBoundsLonLat(n.id);
    // Easternmost ENU x of the tile's east edge (the box may reach past it by its curvature pad,
    // well under 1 % of the tile).
    const double side = kNodeQuads * nodeQuadSizeM(n.id);
    const double xEast = frame.toLocal({0.5 * (b.southDeg + b.northDeg), b.eastDeg, d.minHeightM}).x;
    behind += xEast < -0.01 * side;
  }
  EXPECT_EQ(behind, 0) << "of " << east.nodes.size() << " leaves lie behind the camera";
  ASSERT_LT(d.bounds.westDeg, frame.origin().lonDeg - 0.1);  // half the dataset is behind
}

TEST(TileSelection, AnyDepthConventionGivesTheSameSelection) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  const glm::dvec3 eye = frame.toLocal({d.bounds.centre().y, d.bounds.centre().x, d.maxHeightM + 500.0});
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.3, 1.0, -0.4));
  const glm::dmat4 view = glm::lookAt(eye, eye + dir, glm::dvec3(0, 0, 1));
  const double aspect = 1920.0 / 1080.0;
  // Vulkan [0, 1]; OpenGL [-1, 1]; reverse-Z with an infinite far plane (z_clip = near).
  const glm::dmat4 zeroToOne = glm::perspectiveRH_ZO(kFovY, aspect, 1.0, 1e6);
  const glm::dmat4 minusOneToOne = glm::perspectiveRH_NO(kFovY, aspect, 1.0, 1e6);
  glm::dmat4 reverseInfinite = zeroToOne;
  reverseInfinite[2][2] = 0.0;
  reverseInfinite[3][2] = 1.0;
  const SelectionOptions o{2.0, 100'000};
  const Selection a = selectTiles({eye, zeroToOne * view, 1080.0, kFovY}, d, frame, o);
  const Selection b = selectTiles({eye, minusOneToOne * view, 1080.0, kFovY}, d, frame, o);
  const Selection c = selectTiles({eye, reverseInfinite * view, 1080.0, kFovY}, d, frame, o);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.nodes.size(), c.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].id, b.nodes[i].id);
    EXPECT_EQ(a.nodes[i].id, c.nodes[i].id);
  }
}

TEST(TileSelection, MovingCloserNeverCoarsensTheLeafUnderTheCamera) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  const glm::dvec2 p = {d.bounds.westDeg + 0.3 * d.bounds.widthDeg(), d.bounds.southDeg + 0.6 * d.bounds.heightDeg()};
  const SelectionOptions o{2.0, 100'000};
  int previous = -1, steps = 0;
  for (double h = 60'000.0; h > d.maxHeightM + 20.0; h = d.maxHeightM + 0.8 * (h - d.maxHeightM)) {
    const Selection s = selectTiles(topDown(frame, p.x, p.y, h), d, frame, o);
    int z = -1;
    for (const SelectedNode& n : s.nodes) {
      const geo::GeoBounds b = geo::tileBoundsLonLat(n.id);
      if (p.x >= b.westDeg && p.x < b.eastDeg && p.y > b.southDeg && p.y <= b.northDeg) z = n.id.z;
    }
    ASSERT_GE(z, 0) << "no leaf under the camera at " << h << " m";
    EXPECT_GE(z, previous) << "at " << h << " m";
    previous = z;
    ++steps;
  }
  EXPECT_GT(steps, 20);
  EXPECT_EQ(previous, d.maxZoom) << "low over the terrain the finest level is drawn";
}

TEST(TileSelection, DeterministicAndWantedTilesAreMostUrgentFirst) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  const glm::dvec3 eye = frame.toLocal({d.bounds.centre().y, d.bounds.centre().x, d.maxHeightM + 200.0});
  const SelectionView v = camera(eye, glm::normalize(glm::dvec3(-1.0, 0.2, -0.3)));
  const SelectionOptions o{1.5, 300};
  const Selection a = selectTiles(v, d, frame, o);
  const Selection b = selectTiles(v, d, frame, o);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].id, b.nodes[i].id);
    EXPECT_EQ(a.nodes[i].projectedErrorPx, b.nodes[i].projectedErrorPx);
    EXPECT_EQ(a.nodes[i].distanceM, b.nodes[i].distanceM);
  }
  EXPECT_EQ(a.budgetLimited, b.budgetLimited);
  EXPECT_EQ(a.achievedErrorPx, b.achievedErrorPx);

  const auto wants = wantedTiles(a);
  std::set<geo::TileId> ids, nodes;
  for (const SelectedNode& n : a.nodes) nodes.insert(n.id);
  ASSERT_EQ(wants.size(), a.nodes.size());
  for (size_t i = 0; i < wants.size(); ++i) {
    ids.insert(wants[i].first);
    if (i > 0) {
      EXPECT_GE(wants[i - 1].second, wants[i].second);
    }
  }
  EXPECT_EQ(ids, nodes);
  // Equal priorities (max-zoom nodes at equal distance are rare; build a tie): nearer first.
  Selection tie;
  tie.nodes = {{{14, 1, 1}, 3.0, 900.0}, {{14, 1, 2}, 3.0, 100.0}, {{14, 1, 3}, 5.0, 2000.0}};
  const auto w = wantedTiles(tie);
  EXPECT_EQ(w[0].first, (geo::TileId{14, 1, 3}));
  EXPECT_EQ(w[1].first, (geo::TileId{14, 1, 2}));
  EXPECT_EQ(w[2].first, (geo::TileId{14, 1, 1}));
}

TEST(TileSelection, ResidentHeightRangesTightenTheBoxes) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  const SelectionView v = topDown(frame, d.bounds.centre().x, d.bounds.centre().y, d.maxHeightM + 3000.0);
  const SelectionOptions o{2.0, 100'000};
  const Selection loose = selectTiles(v, d, frame, o);
  // Every tile known to lie at the lowest height: boxes shrink to it, so the camera is farther
  // from them and fewer refinements are needed.
  const float lo = static_cast<float>(d.minHeightM);
  const Selection tight = selectTiles(v, d, frame, o, [lo](const geo::TileId&) {
    return std::optional<std::pair<float, float>>({lo, lo});
  });
  EXPECT_LT(tight.nodes.size(), loose.nodes.size());
  EXPECT_LT(tight.achievedErrorPx, loose.achievedErrorPx);
  // An empty range (all nodata) is ignored rather than trusted.
  const Selection ignored = selectTiles(v, d, frame, o, [](const geo::TileId&) {
    return std::optional<std::pair<float, float>>({1.0f, 0.0f});
  });
  EXPECT_EQ(ignored.nodes.size(), loose.nodes.size());
}

TEST(TileSelection, GeometricErrorHalvesPerLevel) {
  const geo::TileId t = geo::tileContaining({-113.0, 37.3}, 12);
  // 2^12 tiles of 32 quads around 40 075 km · cos 37.3° ≈ 31 870 km: 243 m quads.
  EXPECT_NEAR(nodeQuadSizeM(t), 243.0, 2.0);
  EXPECT_DOUBLE_EQ(nodeGeometricErrorM(t), kErrorPerQuad * nodeQuadSizeM(t));
  const geo::TileId c = geo::children(t)[0];
  EXPECT_NEAR(nodeGeometricErrorM(c) / nodeGeometricErrorM(t), 0.5, 1e-3);
  SelectionView v;
  v.viewportHeightPx = 1000.0;
  v.verticalFovRad = 2.0 * std::atan(0.5);  // 2 tan(fov/2) = 1: px = error · 1000 / d
  EXPECT_NEAR(projectedErrorPx(2.0, 1000.0, v), 2.0, 1e-12);
}

}  // namespace

void expectSameSelection(const Selection& a, const Selection& b, const std::string& where) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size()) << where;
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    ASSERT_EQ(a.nodes[i].id, b.nodes[i].id) << where;
    ASSERT_EQ(a.nodes[i].projectedErrorPx, b.nodes[i].projectedErrorPx) << where;
    ASSERT_EQ(a.nodes[i].distanceM, b.nodes[i].distanceM) << where;
  }
  ASSERT_EQ(a.achievedErrorPx, b.achievedErrorPx) << where;
  ASSERT_EQ(a.budgetLimited, b.budgetLimited) << where;
}

TEST(NodeBoxes, AMemoKeptAlongAFlightGivesTheSameSelectionsBitForBit) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  const SelectionOptions o{2.0, 384};
  // A small memo, so that it also starts again empty on the way; and resident ranges that change
  // under it halfway (a tile's range arriving), which it must not answer from the old box.
  NodeBoxes memo(600), roomy;
  const glm::dvec3 start = frame.toLocal({d.bounds.southDeg + 0.03, d.bounds.westDeg + 0.03, d.maxHeightM + 300.0});
  for (int i = 0; i < 40; ++i) {
    const glm::dvec3 eye = start + glm::dvec3(60.0 * i, 45.0 * i, -4.0 * i);
    const double turn = 0.03 * i;
    const SelectionView v = camera(eye, glm::normalize(glm::dvec3(std::cos(turn), std::sin(turn), -0.2)));
    const float lo = static_cast<float>(d.minHeightM), hi = static_cast<float>(d.minHeightM + 100.0 + i);
    const TileHeightRange ranges = [&](const geo::TileId& t) -> std::optional<std::pair<float, float>> {
      if (i < 20 || (t.x + t.y) % 3 != 0) return std::nullopt;
      return std::pair<float, float>{lo, hi};
    };
    const Selection plain = selectTiles(v, d, frame, o, ranges);
    expectSameSelection(plain, selectTiles(v, d, frame, o, ranges, &memo), "frame " + std::to_string(i));
    expectSameSelection(plain, selectTiles(v, d, frame, o, ranges, &roomy), "frame " + std::to_string(i));
  }
  EXPECT_LE(memo.size(), 600u);
  // Most lookups of a flight are answered from the memo: the views overlap from frame to frame
  // (here a third of the tiles' ranges change every frame of the second half: those miss).
  EXPECT_GT(roomy.hits(), 3 * roomy.misses()) << roomy.hits() << " hits, " << roomy.misses() << " misses";
  EXPECT_GT(memo.misses(), roomy.misses()) << "the small memo started again";
}

TEST(NodeBoxes, TheBoxHoldsTheNodesSurfaceAndItsErrorIsTheSelections) {
  const SelectionDataset d = zionDataset();
  const geo::LocalFrame frame = zionFrame();
  const geo::TileId t = geo::tilesCovering(d.bounds, 12).front();
  const NodeBox b = nodeBox(t, d.minHeightM, d.maxHeightM, frame);
  EXPECT_EQ(b.errorM, nodeGeometricErrorM(t));
  // Points of the tile at both extreme heights and between, off the nine sampled ones.
  for (const double fx : {0.1, 0.37, 0.9})
    for (const double fy : {0.2, 0.61, 0.95})
      for (const double h : {d.minHeightM, 0.5 * (d.minHeightM + d.maxHeightM), d.maxHeightM}) {
        const glm::dvec2 ll = geo::tileXYToLonLat({t.x + fx, t.y + fy}, t.z);
        const glm::dvec3 p = frame.toLocal({ll.y, ll.x, h});
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, b.lo)) && glm::all(glm::lessThanEqual(p, b.hi)))
            << fx << ", " << fy << ", " << h;
      }
}

}  // namespace vegstream::terrain
