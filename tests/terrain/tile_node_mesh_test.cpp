// One selected node's mesh from the Zion sample's real heights (zoom 11 import, zion_tiles.h):
// sampling of the node's tile and of ancestors, shared edges, skirts, nodata, morph deltas,
// and the round trip back to latitude/longitude.

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "terrain/tile_node_mesh.h"
#include "tests/terrain/zion_tiles.h"

namespace vegstream::terrain {
namespace {

constexpr int kQ = kNodeQuads;

// A zoom-11 tile in the middle of the sample (all heights valid there) and the frame.
struct Zion {
  test::ZionTiles& tiles = test::ZionTiles::get();
  geo::TileId t11 = geo::tileContaining(tiles.meta().bounds.centre(), 11);
  geo::LocalFrame frame =
      geo::frameAtCentre(tiles.meta().bounds, 0.5 * (tiles.meta().minHeightM + tiles.meta().maxHeightM));
  const datasets::HeightTile& tile(const geo::TileId& id) { return tiles.tile(id); }
};

glm::dvec2 vertexLonLat(const geo::TileId& n, int i, int j) {
  return geo::tileXYToLonLat({n.x + static_cast<double>(i) / kQ, n.y + static_cast<double>(j) / kQ}, n.z);
}

// Reference bilinear sample through latitude/longitude and the tile's pixel mapping (a second
// path to the same point), clamped at the outermost pixel centres.
double referenceHeight(const datasets::HeightTile& t, glm::dvec2 lonLat) {
  const glm::dvec2 px = geo::lonLatToPixel(t.id, lonLat, t.size);
  const double gx = std::clamp(px.x - 0.5, 0.0, t.size - 1.0), gy = std::clamp(px.y - 0.5, 0.0, t.size - 1.0);
  const int x0 = std::min(static_cast<int>(gx), t.size - 2), y0 = std::min(static_cast<int>(gy), t.size - 2);
  const double fx = gx - x0, fy = gy - y0;
  return (t.at(x0, y0) * (1 - fx) + t.at(x0 + 1, y0) * fx) * (1 - fy) +
         (t.at(x0, y0 + 1) * (1 - fx) + t.at(x0 + 1, y0 + 1) * fx) * fy;
}

glm::dvec3 absolute(const NodeMesh& m, uint32_t v) { return m.mesh.origin + glm::dvec3(m.mesh.vertices[v].position); }
uint32_t grid(int i, int j) { return static_cast<uint32_t>(j * kGridSide + i); }

TEST(TileNodeMesh, OwnTileVerticesSampleItsPixels) {
  Zion z;
  const datasets::HeightTile& t = z.tile(z.t11);
  for (const float h : t.heights) ASSERT_FALSE(std::isnan(h)) << "the test tile must be all data";
  const NodeMesh m = buildNodeMesh(z.t11, {&t}, z.frame);
  ASSERT_EQ(m.mesh.vertices.size(), kGridVertices + kSkirtVertices);
  EXPECT_EQ(m.mesh.triangleCount(), static_cast<size_t>(2 * kQ * kQ + 2 * 4 * kQ));
  EXPECT_EQ(m.sourceLevelsUp, 0);
  // Vertex i lies at pixel coordinate 8i, between the centres of pixels 8i − 1 and 8i: its
  // height is the mean of those 2 × 2 pixels (one pixel's value at the clamped tile edges).
  double worst = 0.0;
  for (int j = 0; j <= kQ; ++j)
    for (int i = 0; i <= kQ; ++i) {
      const int x0 = std::max(8 * i - 1, 0), x1 = std::min(8 * i, 255), y0 = std::max(8 * j - 1, 0), y1 = std::min(8 * j, 255);
      const double mean = (double(t.at(x0, y0)) + t.at(x1, y0) + t.at(x0, y1) + t.at(x1, y1)) / 4.0;
      worst = std::max(worst, std::abs(m.mesh.vertices[grid(i, j)].heightMsl - mean));
    }
  EXPECT_LT(worst, 1e-3);
  // Four levels below the tile, every other vertex lies exactly on one of its pixel centres
  // (pixel coordinate 16a + i/2): there the height is the pixel's height.
  const geo::TileId fine{15, z.t11.x * 16 + 5, z.t11.y * 16 + 9};
  const NodeMesh f = buildNodeMesh(fine, {&t}, z.frame);
  EXPECT_EQ(f.sourceLevelsUp, 4);
  int centres = 0;
  for (int j = 1; j <= kQ; j += 2)
    for (int i = 1; i <= kQ; i += 2) {
      const float pixel = t.at(16 * 5 + (i - 1) / 2, 16 * 9 + (j - 1) / 2);
      EXPECT_EQ(f.mesh.vertices[grid(i, j)].heightMsl, pixel) << i << "," << j;
      ++centres;
    }
  EXPECT_EQ(centres, 256);
}

TEST(TileNodeMesh, AncestorSourcesAreSampledBilinearly) {
  Zion z;
  for (int up = 1; up <= 2; ++up) {
    geo::TileId a = z.t11;
    for (int k = 0; k < up; ++k) a = geo::parent(a);
    const datasets::HeightTile& src = z.tile(a);
    const NodeMesh m = buildNodeMesh(z.t11, {&src}, z.frame);
    EXPECT_EQ(m.sourceLevelsUp, up);
    double worstH = 0.0, worstP = 0.0;
    for (int j = 0; j <= kQ; ++j)
      for (int i = 0; i <= kQ; ++i) {
        const glm::dvec2 ll = vertexLonLat(z.t11, i, j);
        const double h = referenceHeight(src, ll);
        worstH = std::max(worstH, std::abs(m.mesh.vertices[grid(i, j)].heightMsl - h));
        worstP = std::max(worstP, glm::length(absolute(m, grid(i, j)) - z.frame.toLocal({ll.y, ll.x, h})));
      }
    EXPECT_LT(worstH, 1e-3) << up << " levels up";
    EXPECT_LT(worstP, 2e-3) << up << " levels up";
  }
}

// Two same-level neighbours from the same source data: shared edge vertices coincide.
double edgeGap(const NodeMesh& a, const NodeMesh& b, bool eastNeighbour, double* normalGap) {
  double worst = 0.0;
  *normalGap = 0.0;
  for (int k = 0; k <= kQ; ++k) {
    const uint32_t va = eastNeighbour ? grid(kQ, k) : grid(k, kQ);
    const uint32_t vb = eastNeighbour ? grid(0, k) : grid(k, 0);
    worst = std::max(worst, glm::length(absolute(a, va) - absolute(b, vb)));
    *normalGap = std::max(*normalGap, double(glm::length(a.mesh.vertices[va].normal - b.mesh.vertices[vb].normal)));
  }
  return worst;
}

TEST(TileNodeMesh, SameLevelNeighboursFromTheSameSourceShareTheirEdges) {
  Zion z;
  double normalGap = 0.0;
  // Zoom 12 siblings drawn from their zoom-11 parent, zoom 11 siblings from their zoom-10 parent.
  for (const geo::TileId& p : {z.t11, geo::parent(z.t11)}) {
    const datasets::HeightTile& src = z.tile(p);
    const auto c = geo::children(p);  // NW, NE, SW, SE
    const NodeMesh nw = buildNodeMesh(c[0], {&src}, z.frame), ne = buildNodeMesh(c[1], {&src}, z.frame);
    const NodeMesh sw = buildNodeMesh(c[2], {&src}, z.frame);
    SCOPED_TRACE(geo::toString(p));
    EXPECT_LT(edgeGap(nw, ne, true, &normalGap), 1e-3);
    EXPECT_LT(normalGap, 1e-5);
    EXPECT_LT(edgeGap(nw, sw, false, &normalGap), 1e-3);
    EXPECT_LT(normalGap, 1e-5);
  }
}

TEST(TileNodeMesh, SkirtsDropAtLeastTheGeometricError) {
  Zion z;
  const datasets::HeightTile& t = z.tile(z.t11);
  const datasets::HeightTile& g = z.tile(geo::parent(geo::parent(z.t11)));
  const geo::TileId c = geo::children(geo::children(z.t11)[3])[1];
  struct Case { geo::TileId node; const datasets::HeightTile* src; };
  for (const Case& k : {Case{z.t11, &t}, Case{z.t11, &g}, Case{c, &t}, Case{c, &g}}) {
    const NodeMesh m = buildNodeMesh(k.node, {k.src}, z.frame);
    SCOPED_TRACE(geo::toString(k.node) + " from " + geo::toString(k.src->id));
    EXPECT_GE(m.skirtDepthM, nodeGeometricErrorM(k.node));
    EXPECT_GE(m.skirtDepthM, 5.0);
    EXPECT_DOUBLE_EQ(m.skirtDepthM, skirtDepthM(k.node, m.sourceLevelsUp, 5.0));
    double shallowest = std::numeric_limits<double>::max();
    for (uint32_t s = kGridVertices; s < kGridVertices + kSkirtVertices; ++s) {
      const TerrainVertex& v = m.mesh.vertices[s];
      const uint32_t top = grid(static_cast<int>(std::lround(v.uv.x * kQ)), static_cast<int>(std::lround(v.uv.y * kQ)));
      const geo::Geodetic a = z.frame.toGeodetic(absolute(m, top)), b = z.frame.toGeodetic(absolute(m, s));
      shallowest = std::min(shallowest, a.heightM - b.heightM);
      EXPECT_NEAR(glm::length(absolute(m, top) - absolute(m, s)), m.skirtDepthM, 2e-3);
    }
    EXPECT_NEAR(shallowest, m.skirtDepthM, 2e-3);
    EXPECT_GE(shallowest + 2e-3, nodeGeometricErrorM(k.node));
  }
}

TEST(TileNodeMesh, NodataLeavesHolesNotZeros) {
  Zion z;
  datasets::HeightTile t = z.tile(z.t11);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // The 2 × 2 pixels under vertex (16, 16): that vertex alone becomes nodata, 6 triangles go.
  for (int y = 127; y <= 128; ++y)
    for (int x = 127; x <= 128; ++x) t.heights[static_cast<size_t>(y * 256 + x)] = nan;
  const NodeMesh m = buildNodeMesh(z.t11, {&t}, z.frame);
  EXPECT_EQ(m.mesh.triangleCount(), static_cast<size_t>(2 * kQ * kQ + 8 * kQ - 6));
  for (const uint32_t i : m.mesh.indices) {
    ASSERT_NE(i, grid(16, 16));
    ASSERT_GT(m.mesh.vertices[i].heightMsl, 900.0f) << "a drawn vertex fell towards zero";
  }
  // Column 0 of pixels: the west edge vertices go, with their 64 grid triangles and the skirt
  // segments along the west edge (32) and at the two western corners (2).
  for (int y = 0; y < 256; ++y) t.heights[static_cast<size_t>(y * 256)] = nan;
  const NodeMesh w = buildNodeMesh(z.t11, {&t}, z.frame);
  EXPECT_EQ(w.mesh.triangleCount(), static_cast<size_t>(2 * kQ * kQ - 6 - 2 * kQ + 8 * kQ - 2 * 34));
  for (const uint32_t i : w.mesh.indices) ASSERT_GT(w.mesh.vertices[i].heightMsl, 900.0f);
}

TEST(TileNodeMesh, MorphDeltaIsCoarseMinusFine) {
  Zion z;
  const datasets::HeightTile& t = z.tile(z.t11);
  const datasets::HeightTile& p = z.tile(geo::parent(z.t11));
  const NodeMesh plain = buildNodeMesh(z.t11, {&t}, z.frame);
  for (const TerrainVertex& v : plain.mesh.vertices) ASSERT_EQ(v.morphDelta, 0.0f);

  NodeMeshOptions options;
  options.coarse = HeightSource{&p};
  const NodeMesh m = buildNodeMesh(z.t11, {&t}, z.frame, options);
  double worst = 0.0, largest = 0.0, boundaryLargest = 0.0;
  for (int j = 0; j <= kQ; ++j)
    for (int i = 0; i <= kQ; ++i) {
      const glm::dvec2 ll = vertexLonLat(z.t11, i, j);
      const double expected = referenceHeight(p, ll) - referenceHeight(t, ll);
      const double got = m.mesh.vertices[grid(i, j)].morphDelta;
      worst = std::max(worst, std::abs(got - expected));
      largest = std::max(largest, std::abs(expected));
      if (i == 0 || j == 0 || i == kQ || j == kQ) boundaryLargest = std::max(boundaryLargest, std::abs(got));
    }
  EXPECT_LT(worst, 2e-3);
  EXPECT_GT(largest, 1.0) << "Zion's parent tile differs from the child by metres somewhere";
  // The skirt also covers the largest morph offset on the boundary.
  EXPECT_NEAR(m.skirtDepthM, skirtDepthM(z.t11, 0, options.minSkirtDepthM) + boundaryLargest, 1e-9);
  for (uint32_t s = kGridVertices; s < kGridVertices + kSkirtVertices; ++s) {
    const TerrainVertex& v = m.mesh.vertices[s];
    const uint32_t top = grid(static_cast<int>(std::lround(v.uv.x * kQ)), static_cast<int>(std::lround(v.uv.y * kQ)));
    EXPECT_EQ(v.morphDelta, m.mesh.vertices[top].morphDelta);
  }
}

TEST(TileNodeMesh, VerticesRoundTripIntoTheNodeTile) {
  Zion z;
  const datasets::HeightTile& t = z.tile(z.t11);
  const datasets::HeightTile& g = z.tile(geo::parent(geo::parent(z.t11)));
  const geo::TileId fine = geo::children(geo::children(z.t11)[2])[1];
  for (const auto& [node, src] : {std::pair{z.t11, &t}, std::pair{fine, &g}}) {
    const NodeMesh m = buildNodeMesh(node, {src}, z.frame);
    const geo::GeoBounds b = geo::tileBoundsLonLat(node);
    const double tol = 1e-8;  // degrees, about 1 mm
    for (uint32_t v = 0; v < m.mesh.vertices.size(); ++v) {
      const geo::Geodetic p = z.frame.toGeodetic(absolute(m, v));
      ASSERT_GE(p.lonDeg, b.westDeg - tol) << v;
      ASSERT_LE(p.lonDeg, b.eastDeg + tol) << v;
      ASSERT_GE(p.latDeg, b.southDeg - tol) << v;
      ASSERT_LE(p.latDeg, b.northDeg + tol) << v;
      if (v < kGridVertices) {
        EXPECT_NEAR(p.heightM, m.mesh.vertices[v].heightMsl, 2e-3) << v;
      }
    }
    // The corners sit on the tile's corners.
    const geo::Geodetic nw = z.frame.toGeodetic(absolute(m, grid(0, 0))), se = z.frame.toGeodetic(absolute(m, grid(kQ, kQ)));
    EXPECT_NEAR(nw.lonDeg, b.westDeg, tol);
    EXPECT_NEAR(nw.latDeg, b.northDeg, tol);
    EXPECT_NEAR(se.lonDeg, b.eastDeg, tol);
    EXPECT_NEAR(se.latDeg, b.southDeg, tol);
    EXPECT_EQ(m.mesh.vertices[grid(kQ, 0)].uv, glm::vec2(1.0f, 0.0f));  // u east, v south
  }
}

TEST(TileNodeMesh, GridFacesUpSkirtsFaceOutNormalsAreUnit) {
  Zion z;
  const datasets::HeightTile& t = z.tile(z.t11);
  const NodeMesh m = buildNodeMesh(z.t11, {&t}, z.frame);
  const size_t gridIndices = static_cast<size_t>(6 * kQ * kQ);
  for (size_t k = 0; k < m.mesh.indices.size(); k += 3) {
    const glm::dvec3 a = absolute(m, m.mesh.indices[k]), b = absolute(m, m.mesh.indices[k + 1]),
                     c = absolute(m, m.mesh.indices[k + 2]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    if (k < gridIndices) {
      ASSERT_GT(n.z, 0.0) << "grid triangle " << k / 3;
    } else {
      const glm::dvec3 out = (a + b + c) / 3.0 - m.mesh.origin;
      ASSERT_GT(n.x * out.x + n.y * out.y, 0.0) << "skirt triangle " << k / 3 << " faces inwards";
    }
  }
  for (const TerrainVertex& v : m.mesh.vertices) {
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
    EXPECT_GT(v.normal.z, 0.3f);  // Zion's 256 m quads are never steeper than ~73°
  }
}

}  // namespace
}  // namespace vegstream::terrain
