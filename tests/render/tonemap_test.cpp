// Exposure and tone mapping (render/tonemap_pass.h): deterministic automatic exposure, a fixed
// exposure that does what EV says, a daylight frame in the middle of the display range with its
// sky unclipped.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "gpu_test_fixture.h"

namespace vegstream::render::testing {
namespace {

constexpr uint32_t kW = 160, kH = 90;

// Rec. 709 luma of the sRGB-encoded values, 0 … 1, over the rows [y0, y1).
double meanLuma(const ColorImage& img, uint32_t y0, uint32_t y1) {
  double sum = 0.0;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < img.width; ++x) {
      const uint8_t* p = &img.rgba[(size_t{y} * img.width + x) * 4];
      sum += (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]) / 255.0;
    }
  return sum / (double(y1 - y0) * img.width);
}

class TonemapTest : public GpuTest {
 protected:
  terrain::TerrainMesh plane = flatPlane(40'000.0, 8, 0.0f);
  TerrainDraw draw{&plane};

  // Eye height over a plane, looking level towards the north, the sun 45° up in the south-east.
  FrameRequest eyeHeight() {
    FrameRequest req;
    req.camera.position = {0.0, 0.0, 1.7};
    req.cameraHeightMsl = 1.7;
    const double e = glm::radians(45.0);
    req.lighting.sunDirection = {std::cos(e) * 0.7, -std::cos(e) * 0.7, std::sin(e)};
    req.readbackColor = true;
    req.terrain = {&draw, 1};
    return req;
  }
};

TEST_F(TonemapTest, TheSameFrameTwiceGivesTheSameBytesAndExposure) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  auto a = r->renderFrame(eyeHeight());
  auto b = r->renderFrame(eyeHeight());
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->color->rgba, b->color->rgba);
  EXPECT_EQ(a->exposureEv, b->exposureEv);
  EXPECT_GT(a->exposureEv, 10.0f);  // a sunny scene: EV100 ~ 13–16
  EXPECT_LT(a->exposureEv, 18.0f);
}

TEST_F(TonemapTest, AFixedExposureIsUsedAndOneStopMoreIsBrighter) {
  auto r = makeRenderer(kW, kH, 1);
  ASSERT_TRUE(r);
  FrameRequest req = eyeHeight();
  req.lighting.exposureEv = 14.0f;
  auto dark = r->renderFrame(req);
  req.lighting.exposureEv = 13.0f;
  auto bright = r->renderFrame(req);
  ASSERT_TRUE(dark.ok() && bright.ok());
  EXPECT_EQ(dark->exposureEv, 14.0f);
  EXPECT_EQ(bright->exposureEv, 13.0f);
  EXPECT_GT(meanLuma(*bright->color, 0, kH), meanLuma(*dark->color, 0, kH) + 0.03);
}

// A daylight still at eye height: its mean luma in 0.35 … 0.65, at most 1 % of its sky at 255.
TEST_F(TonemapTest, ADaylightStillIsMidRangeWithItsSkyUnclipped) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  FrameRequest req = eyeHeight();
  req.readbackDepth = true;
  auto f = r->renderFrame(req);
  ASSERT_TRUE(f.ok());
  const double luma = meanLuma(*f->color, 0, kH);
  EXPECT_GT(luma, 0.35);
  EXPECT_LT(luma, 0.65);
  size_t sky = 0, clipped = 0;
  for (size_t i = 0; i < f->depth->depth.size(); ++i) {
    if (f->depth->depth[i] != 0.0f) continue;
    ++sky;
    const uint8_t* p = &f->color->rgba[i * 4];
    if (p[0] == 255 || p[1] == 255 || p[2] == 255) ++clipped;
  }
  ASSERT_GT(sky, size_t{kW * kH / 4});
  EXPECT_LE(clipped, sky / 100);
}

}  // namespace
}  // namespace vegstream::render::testing
