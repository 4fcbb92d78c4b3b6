// The foundation's grid mesh and height sampling.

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "terrain/grid_mesh.h"

namespace vegstream::terrain {
namespace {

HeightGrid rampGrid(int w, int h) {
  HeightGrid g;
  g.width = w;
  g.height = h;
  g.lonFirst = -113.0;
  g.latFirst = 37.5;
  g.lonStep = 0.001;
  g.latStep = -0.001;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) g.heights.push_back(static_cast<float>(1000.0 + 2.0 * c + 3.0 * r));
  return g;
}

TEST(HeightGrid, BilinearSamplingAndNodata) {
  HeightGrid g = rampGrid(5, 4);
  EXPECT_DOUBLE_EQ(g.sample(1.5, 2.25), 1000.0 + 3.0 + 6.75);  // a plane is reproduced exactly
  EXPECT_NEAR(g.sampleLonLat(-113.0 + 0.0025, 37.5 - 0.001), 1000.0 + 5.0 + 3.0, 1e-6);
  EXPECT_TRUE(std::isnan(g.sample(-0.1, 1.0)));
  EXPECT_TRUE(std::isnan(g.sample(1.0, 3.5)));
  g.heights[static_cast<size_t>(1 * 5 + 2)] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(g.sample(1.5, 0.5)));
  EXPECT_FALSE(std::isnan(g.sample(3.5, 2.5)));
}

TEST(GridMesh, TriangleCountsStepsAndNodataHoles) {
  HeightGrid g = rampGrid(9, 7);
  const geo::LocalFrame frame({g.centreLat(), g.centreLon(), 0.0});
  EXPECT_EQ(buildGridMesh(g, frame).triangleCount(), 2u * 8 * 6);
  EXPECT_EQ(buildGridMesh(g, frame, {2}).triangleCount(), 2u * 4 * 3);
  // One interior nodata sample removes the six triangles that touch it.
  g.heights[static_cast<size_t>(3 * 9 + 4)] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(buildGridMesh(g, frame).triangleCount(), 2u * 8 * 6 - 6);
}

TEST(GridMesh, VerticesSitInTheLocalFrameWithCurvature) {
  HeightGrid g;
  g.width = 201;
  g.height = 3;
  g.lonFirst = -113.25;  // ±0.25° of longitude ≈ ±22 km at 37.3°N
  g.latFirst = 37.301;
  g.lonStep = 0.0025;
  g.latStep = -0.001;
  g.heights.assign(static_cast<size_t>(g.width * g.height), 0.0f);  // all at sea level
  const geo::LocalFrame frame({g.centreLat(), g.centreLon(), 0.0});
  const TerrainMesh mesh = buildGridMesh(g, frame);
  const TerrainVertex& centre = mesh.vertices[static_cast<size_t>(g.width + 100)];
  const TerrainVertex& east = mesh.vertices[static_cast<size_t>(g.width + 200)];
  EXPECT_NEAR(centre.position.x, 0.0, 1e-3);
  EXPECT_NEAR(east.position.x, 22'150.0, 100.0);
  // Earth curvature: the edge sits d²/2R ≈ 38.5 m below the tangent plane.
  EXPECT_NEAR(east.position.z, -(22'150.0 * 22'150.0) / (2 * 6'371'000.0), 1.0);
  // A level surface's normal is the local up: it tilts east by ~d/R at the edge.
  EXPECT_NEAR(glm::length(east.normal), 1.0f, 1e-5f);
  EXPECT_NEAR(east.normal.x, 22'150.0 / 6'371'000.0, 3e-4);
  EXPECT_NEAR(centre.normal.z, 1.0f, 1e-6f);
}

TEST(GridMesh, NormalsFollowSlopeAndTrianglesFaceUp) {
  const HeightGrid g = rampGrid(6, 6);  // rises 2 m per 88 m east, 3 m per 111 m south
  const geo::LocalFrame frame({g.centreLat(), g.centreLon(), 0.0});
  const TerrainMesh mesh = buildGridMesh(g, frame);
  const TerrainVertex& v = mesh.vertices[14];
  EXPECT_LT(v.normal.x, 0.0f);  // uphill to the east: the normal leans west
  EXPECT_GT(v.normal.y, 0.0f);  // uphill to the south: the normal leans north
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.vertices[mesh.indices[t]].position, b = mesh.vertices[mesh.indices[t + 1]].position,
                    c = mesh.vertices[mesh.indices[t + 2]].position;
    ASSERT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t / 3 << " is not counter-clockwise from above";
  }
}

}  // namespace
}  // namespace vegstream::terrain
