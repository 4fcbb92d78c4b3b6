#include "geo/xyz_tiles.h"

#include <cmath>
#include <map>
#include <set>
#include <unordered_set>

#include <gtest/gtest.h>

#include "geo/projection.h"

namespace vegstream::geo {
namespace {

TEST(XyzTiles, KnownTileBounds) {
  // A Zion tile of the grandcanyon-xyz / zion imports.
  const GeoBounds b = tileBoundsLonLat(TileId{12, 758, 1608});
  EXPECT_NEAR(b.westDeg, -113.37890625, 1e-12);
  EXPECT_NEAR(b.eastDeg, -113.291015625, 1e-12);
  EXPECT_NEAR(b.northDeg, 36.031331776332, 1e-11);
  EXPECT_NEAR(b.southDeg, 35.960222969297, 1e-11);

  const ProjectedBounds m = tileBoundsMercator(TileId{12, 758, 1608});
  const double tileM = 2.0 * kWebMercatorHalfWorldM / 4096.0;  // 9783.939620502 m
  EXPECT_NEAR(m.size().x, tileM, 1e-6);
  EXPECT_NEAR(m.size().y, tileM, 1e-6);
  EXPECT_NEAR(m.min.x, -kWebMercatorHalfWorldM + 758 * tileM, 1e-6);
  EXPECT_NEAR(m.max.y, kWebMercatorHalfWorldM - 1608 * tileM, 1e-6);

  const GeoBounds world = tileBoundsLonLat(TileId{0, 0, 0});
  EXPECT_NEAR(world.westDeg, -180.0, 1e-12);
  EXPECT_NEAR(world.eastDeg, 180.0, 1e-12);
  EXPECT_NEAR(world.northDeg, kWebMercatorMaxLatDeg, 1e-12);
  EXPECT_NEAR(world.southDeg, -kWebMercatorMaxLatDeg, 1e-12);
}

TEST(XyzTiles, LonLatToTileAndBack) {
  const glm::dvec2 zion(-113.05, 37.3);
  const glm::dvec2 t = lonLatToTileXY(zion, 12);
  EXPECT_EQ(tileContaining(zion, 12), (TileId{12, 761, 1590}));  // x 761.74, y 1590.004
  EXPECT_NEAR(t.x, (zion.x + 180.0) / 360.0 * 4096.0, 1e-9);
  const glm::dvec2 back = tileXYToLonLat(t, 12);
  EXPECT_NEAR(back.x, zion.x, 1e-12);
  EXPECT_NEAR(back.y, zion.y, 1e-12);
  // Poles clamp onto the pyramid's edge; ±180° belong to the edge tiles.
  EXPECT_NEAR(lonLatToTileXY({0.0, 90.0}, 3).y, 0.0, 1e-9);
  EXPECT_NEAR(lonLatToTileXY({0.0, -90.0}, 3).y, 8.0, 1e-9);
  EXPECT_EQ(tileContaining({180.0, -90.0}, 3), (TileId{3, 7, 7}));
  EXPECT_EQ(tileContaining({-180.0, 90.0}, 3), (TileId{3, 0, 0}));
}

TEST(XyzTiles, PixelsWithinATile) {
  const TileId t{12, 758, 1608};
  const GeoBounds b = tileBoundsLonLat(t);
  const glm::dvec2 nw = pixelToLonLat(t, {0.0, 0.0});
  EXPECT_NEAR(nw.x, b.westDeg, 1e-12);
  EXPECT_NEAR(nw.y, b.northDeg, 1e-12);
  const glm::dvec2 se = pixelToLonLat(t, {512.0, 512.0}, 512);
  EXPECT_NEAR(se.x, b.eastDeg, 1e-12);
  EXPECT_NEAR(se.y, b.southDeg, 1e-12);
  // Centre of pixel (10, 200) in a 256 tile and back.
  const glm::dvec2 ll = pixelToLonLat(t, {10.5, 200.5});
  const glm::dvec2 px = lonLatToPixel(t, ll);
  EXPECT_NEAR(px.x, 10.5, 1e-7);
  EXPECT_NEAR(px.y, 200.5, 1e-7);
  // Pixel pitch in EPSG:3857 metres: 9783.94 m / 256.
  const glm::dvec2 m0 = pixelToMercator(t, {0.0, 0.0});
  const glm::dvec2 m1 = pixelToMercator(t, {1.0, 1.0});
  EXPECT_NEAR(m1.x - m0.x, 38.21851414258813, 1e-9);
  EXPECT_NEAR(m0.y - m1.y, 38.21851414258813, 1e-9);
  const glm::dvec2 pm = mercatorToPixel(t, m1);
  EXPECT_NEAR(pm.x, 1.0, 1e-9);
  EXPECT_NEAR(pm.y, 1.0, 1e-9);
}

TEST(XyzTiles, CoveringCounts) {
  // A tile's own bounds cover exactly that tile (edges on boundaries add no neighbour).
  const TileId t{12, 758, 1608};
  auto one = tilesCovering(tileBoundsLonLat(t), 12);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0], t);
  // …and its 4^3 = 64 descendants three zooms down.
  EXPECT_EQ(tilesCovering(tileBoundsLonLat(t), 15).size(), 64u);
  // The whole world.
  EXPECT_EQ(tilesCovering(GeoBounds{-180.0, -90.0, 180.0, 90.0}, 0).size(), 1u);
  EXPECT_EQ(tilesCovering(GeoBounds{-180.0, -90.0, 180.0, 90.0}, 4).size(), 256u);
  // A point is one tile; a box straddling one corner is four.
  EXPECT_EQ(tilesCovering(GeoBounds{-113.05, 37.3, -113.05, 37.3}, 12).size(), 1u);
  const GeoBounds tb = tileBoundsLonLat(t);
  const GeoBounds corner{tb.eastDeg - 0.001, tb.southDeg - 0.001, tb.eastDeg + 0.001, tb.southDeg + 0.001};
  auto four = tilesCovering(corner, 12);
  ASSERT_EQ(four.size(), 4u);
  EXPECT_EQ(four[0], (TileId{12, 758, 1608}));  // north-west first, row by row
  EXPECT_EQ(four[3], (TileId{12, 759, 1609}));
  // Zion-sized box (0.4° × 0.3°) at z 12: x 760.04 … 764.59 → 5 columns; y 1588.57 … 1592.86
  // → 5 rows.
  const GeoBounds zion{-113.2, 37.1, -112.8, 37.4};
  const auto ranges = tileRangesCovering(zion, 12);
  ASSERT_EQ(ranges.size(), 1u);
  EXPECT_EQ(ranges[0].minX, 760);
  EXPECT_EQ(ranges[0].maxX, 764);
  EXPECT_EQ(ranges[0].minY, 1588);
  EXPECT_EQ(ranges[0].maxY, 1592);
  EXPECT_EQ(ranges[0].count(), 25);
  EXPECT_EQ(ranges[0].count(), static_cast<std::int64_t>(tilesCovering(zion, 12).size()));
  // Every listed tile overlaps the box.
  for (const TileId& id : tilesCovering(zion, 12)) {
    const GeoBounds b = tileBoundsLonLat(id);
    EXPECT_LT(b.westDeg, zion.eastDeg);
    EXPECT_GT(b.eastDeg, zion.westDeg);
    EXPECT_LT(b.southDeg, zion.northDeg);
    EXPECT_GT(b.northDeg, zion.southDeg);
  }
}

TEST(XyzTiles, CoveringAcrossTheAntimeridian) {
  const GeoBounds fiji{177.0, -19.0, -178.0, -16.0};
  EXPECT_NEAR(fiji.widthDeg(), 5.0, 1e-12);
  EXPECT_NEAR(fiji.centre().x, 179.5, 1e-12);
  const auto ranges = tileRangesCovering(fiji, 6);
  ASSERT_EQ(ranges.size(), 2u);
  EXPECT_EQ(ranges[0].maxX, 63);
  EXPECT_EQ(ranges[1].minX, 0);
  // 177° → x 63.47 (1 column), -178° → x 0.36 (1 column); -16°…-19° → y 34.8 … 35.4 (2 rows).
  EXPECT_EQ(tilesCovering(fiji, 6).size(), 4u);
}

TEST(XyzTiles, ParentsChildrenAndHashing) {
  const TileId t{12, 758, 1608};
  EXPECT_EQ(parent(t), (TileId{11, 379, 804}));
  const auto kids = children(t);
  EXPECT_EQ(kids[0], (TileId{13, 1516, 3216}));
  EXPECT_EQ(kids[3], (TileId{13, 1517, 3217}));
  for (const TileId& k : kids) EXPECT_EQ(parent(k), t);
  EXPECT_TRUE(isValid(t));
  EXPECT_FALSE(isValid(TileId{2, 4, 0}));
  EXPECT_FALSE(isValid(TileId{-1, 0, 0}));
  EXPECT_EQ(toString(t), "12/758/1608");
  EXPECT_LT((TileId{11, 900, 900}), t);  // z orders first

  // All 1 + 4 + … + 4^6 tiles of zooms 0…6 hash to distinct buckets' keys (no equal hashes).
  std::unordered_set<std::size_t> hashes;
  std::size_t n = 0;
  for (int z = 0; z <= 6; ++z) {
    for (const TileId& id : tilesCovering(GeoBounds{-180.0, -90.0, 180.0, 90.0}, z)) {
      hashes.insert(std::hash<TileId>{}(id));
      ++n;
    }
  }
  EXPECT_EQ(n, 5461u);
  EXPECT_EQ(hashes.size(), n);
}

TEST(XyzTiles, Resolution) {
  EXPECT_NEAR(mercatorResolution(0), 156543.03392804097, 1e-8);
  EXPECT_NEAR(mercatorResolution(12, 512), 156543.03392804097 / 4096.0 / 2.0, 1e-10);
  // At the equator ground and projected metres agree.
  EXPECT_NEAR(groundResolution(0.0, 0), 156543.03392804097, 1e-8);
  // 37.3°N, z 14: 9.5546 m/px projected × cos φ / sqrt(1 − e² sin² φ) = 7.60981 m/px.
  EXPECT_NEAR(groundResolution(37.3, 14), 7.609813065, 1e-8);
  // The inverse: 10 m/px at 37.3°N needs zoom 13.606; a 1 m source at 45°N z 16.76 → 17.
  EXPECT_NEAR(zoomForResolution(groundResolution(37.3, 14), 37.3), 14.0, 1e-12);
  EXPECT_NEAR(zoomForResolution(10.0, 37.3), 13.605932920, 1e-8);
  EXPECT_NEAR(zoomForResolution(1.0, 45.0), 16.758618322, 1e-8);
}

}  // namespace
}  // namespace vegstream::geo
