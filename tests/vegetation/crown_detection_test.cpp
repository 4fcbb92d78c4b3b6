// vegetation/crown_detection.h (issue 41 item 3; Popescu & Wynne 2004's variable window) on
// synthetic canopy height models made from known trees (tests/support/synthetic_chm.h): the trees
// are found (≥ 90 % within 1.5 m, heights within 1 m RMS, ≤ 10 % extra) on 1 m and 0.5 m grids,
// the same on any window that holds the margin (locality: the scene detects cell tile by cell
// tile), and none where the CHM has no data. Each test prints its figures.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/synthetic_chm.h"
#include "vegetation/crown_detection.h"

namespace vegstream::vegetation {
namespace {

using testing::FoundTree;
using testing::MatchFigures;
using testing::TrueTree;

constexpr double kSideM = 140.0;

std::vector<FoundTree> asFound(const std::vector<DetectedCrown>& crowns, double pixelM) {
  std::vector<FoundTree> out;
  for (const DetectedCrown& c : crowns) out.push_back({c.col * pixelM, c.row * pixelM, c.heightM});
  return out;
}

struct Run {
  MatchFigures m;
  double msPerHa = 0.0;
  double crownRmsM = 0.0;
};

Run detectOn(uint32_t seed, double pixelM) {
  const std::vector<TrueTree> truth = testing::syntheticTrees(150, kSideM, seed);
  EXPECT_EQ(truth.size(), 150u);
  const int side = static_cast<int>(std::lround(kSideM / pixelM));
  const std::vector<float> chm = testing::rasterizeChm(truth, side, pixelM, 0.15f, seed + 1);
  CrownDetectionOptions o;
  o.pixelM = static_cast<float>(pixelM);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<DetectedCrown> crowns = detectCrowns(chm, side, side, o);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  Run r;
  r.m = testing::matchTrees(truth, asFound(crowns, pixelM), 1.5);
  r.msPerHa = ms / (kSideM * kSideM / 1e4);
  // The crowns' radii against the true radii of the nearest found tree (a figure, not asserted).
  double sum = 0.0;
  int n = 0;
  for (const TrueTree& t : truth)
    for (const DetectedCrown& c : crowns)
      if (std::hypot(c.col * pixelM - t.x, c.row * pixelM - t.y) <= 1.5) {
        sum += std::pow(double(c.crownRadiusM - t.radiusM), 2);
        ++n;
        break;
      }
  r.crownRmsM = n ? std::sqrt(sum / n) : 0.0;
  // Close neighbours are there: trees with another within 4 m (crowns touching or overlapping).
  int close = 0;
  for (const TrueTree& a : truth)
    for (const TrueTree& b : truth)
      if (&a != &b && std::hypot(a.x - b.x, a.y - b.y) < 4.0) {
        ++close;
        break;
      }
  std::printf("[ figures  ] %d of %zu trees have a neighbour within 4 m\n", close, truth.size());
  EXPECT_GE(close, 15);
  return r;
}

void expectRecovered(const Run& r, const char* what) {
  std::printf("[ figures  ] %s: %d trees, %d found, %d matched within 1.5 m: recall %.1f %%, extra %.1f %%, "
              "height RMS %.2f m, position RMS %.2f m, crown radius RMS %.2f m; detection %.1f ms/ha\n",
              what, r.m.truth, r.m.found, r.m.matched, 100.0 * r.m.recall, 100.0 * r.m.extraShare, r.m.heightRmsM,
              r.m.positionRmsM, r.crownRmsM, r.msPerHa);
  EXPECT_GE(r.m.recall, 0.90) << what;
  EXPECT_LE(r.m.heightRmsM, 1.0) << what;
  EXPECT_LE(r.m.extraShare, 0.10) << what;
}

TEST(CrownDetection, FindsTheTreesOfAOneMetreChm) {
  for (uint32_t seed : {11u, 12u, 13u}) expectRecovered(detectOn(seed, 1.0), "1 m CHM");
}

TEST(CrownDetection, FindsTheTreesOfAHalfMetreChm) {
  for (uint32_t seed : {21u, 22u}) expectRecovered(detectOn(seed, 0.5), "0.5 m CHM");
}

// A window holding the margin around an area finds exactly the trees of the whole raster there.
TEST(CrownDetection, IsLocalAndDeterministic) {
  const std::vector<TrueTree> truth = testing::syntheticTrees(150, kSideM, 5);
  const int side = 140;
  const std::vector<float> chm = testing::rasterizeChm(truth, side, 1.0, 0.15f, 6);
  CrownDetectionOptions o;
  const std::vector<DetectedCrown> whole = detectCrowns(chm, side, side, o);
  const std::vector<DetectedCrown> again = detectCrowns(chm, side, side, o);
  ASSERT_EQ(whole.size(), again.size());
  for (size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(whole[i].col, again[i].col);
    EXPECT_EQ(whole[i].heightM, again[i].heightM);
  }
  const int m = marginPixels(o);
  const int x0 = 40, y0 = 50, x1 = 90, y1 = 100;  // the area
  const int wx0 = x0 - m, wy0 = y0 - m, w = (x1 - x0) + 2 * m, h = (y1 - y0) + 2 * m;
  std::vector<float> window(size_t(w) * size_t(h));
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) window[size_t(r) * size_t(w) + size_t(c)] = chm[size_t(r + wy0) * side + size_t(c + wx0)];
  auto inArea = [&](double col, double row) { return col >= x0 && col < x1 && row >= y0 && row < y1; };
  std::vector<DetectedCrown> expected, got;
  for (const DetectedCrown& c : whole)
    if (inArea(c.col, c.row)) expected.push_back(c);
  for (DetectedCrown c : detectCrowns(window, w, h, o)) {
    c.col += wx0;
    c.row += wy0;
    if (inArea(c.col, c.row)) got.push_back(c);
  }
  std::printf("[ figures  ] %zu trees in the 50 × 50 m area, margin %d pixels\n", expected.size(), m);
  ASSERT_GT(expected.size(), 5u);
  ASSERT_EQ(got.size(), expected.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_DOUBLE_EQ(got[i].col, expected[i].col);
    EXPECT_DOUBLE_EQ(got[i].row, expected[i].row);
    EXPECT_EQ(got[i].heightM, expected[i].heightM);
    EXPECT_EQ(got[i].crownRadiusM, expected[i].crownRadiusM);
  }
}

TEST(CrownDetection, NoDataAndLowVegetationGiveNoTree) {
  const std::vector<TrueTree> truth = testing::syntheticTrees(150, kSideM, 7);
  const int side = 140;
  std::vector<float> chm = testing::rasterizeChm(truth, side, 1.0, 0.15f, 8);
  for (int r = 0; r < side; ++r)
    for (int c = 0; c < side / 2; ++c) chm[size_t(r) * side + size_t(c)] = NAN;
  const std::vector<DetectedCrown> crowns = detectCrowns(chm, side, side, CrownDetectionOptions{});
  ASSERT_FALSE(crowns.empty());
  for (const DetectedCrown& c : crowns) EXPECT_GE(c.col, side / 2);
  std::vector<float> shrubs(size_t(side) * side, 1.5f);
  EXPECT_TRUE(detectCrowns(shrubs, side, side, CrownDetectionOptions{}).empty());
}

// The detection's cost on a larger stand: the 140 m CHM repeated 4 × 4 (31 ha, 2400 trees), best of 3.
TEST(CrownDetection, TimePerHectare) {
  const std::vector<TrueTree> truth = testing::syntheticTrees(150, kSideM, 41);
  for (double pixelM : {1.0, 0.5}) {
    const int side = static_cast<int>(std::lround(kSideM / pixelM)), big = 4 * side;
    const std::vector<float> chm = testing::rasterizeChm(truth, side, pixelM, 0.15f, 42);
    std::vector<float> tiled(size_t(big) * size_t(big));
    for (int r = 0; r < big; ++r)
      for (int c = 0; c < big; ++c) tiled[size_t(r) * big + size_t(c)] = chm[size_t(r % side) * side + size_t(c % side)];
    CrownDetectionOptions o;
    o.pixelM = static_cast<float>(pixelM);
    double best = INFINITY;
    size_t found = 0;
    for (int k = 0; k < 3; ++k) {
      const auto start = std::chrono::steady_clock::now();
      found = detectCrowns(tiled, big, big, o).size();
      best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    const double ha = std::pow(4.0 * kSideM, 2) / 1e4;
    std::printf("[ figures  ] %.1f m pixels: %zu trees in %.1f ha in %.1f ms: %.2f ms/ha\n", pixelM, found, ha, best,
                best / ha);
    EXPECT_GE(found, 16u * 140u);
  }
}

TEST(CrownDetection, WindowFollowsPopescuWynne) {
  // CW = 2.51503 + 0.00901 h² (PE&RS 2004, pines and deciduous together): 10.62 m at 30 m.
  EXPECT_NEAR(popescuWynneCrownWidthM(30.0f), 10.624f, 1e-3f);
  CrownDetectionOptions o;
  EXPECT_NEAR(windowRadiusM(o, 30.0f), 0.25f * 10.624f, 1e-3f);
  EXPECT_EQ(windowRadiusM(o, 2.0f), o.minWindowM);
  EXPECT_EQ(windowRadiusM(o, 100.0f), o.maxWindowM);
}

}  // namespace
}  // namespace vegstream::vegetation
