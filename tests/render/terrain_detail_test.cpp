// The terrain pass's close-up detail textures on the real driver (lavapipe here): visible near
// the camera, gone far away (exactly the imagery), anchored to the world rather than the camera,
// and chosen by the colour score of the imagery under them.

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "gpu_test_fixture.h"
#include "render/png_writer.h"
#include "render/terrain_detail.h"

namespace vegstream::render::testing {
namespace {

constexpr uint32_t kW = 320, kH = 180;

struct Rgb8 {
  uint8_t r, g, b;
};

class TerrainDetailTest : public GpuTest {
 protected:
  void SetUp() override {
    renderer = makeRenderer(kW, kH, 1);
    ASSERT_TRUE(renderer);
    ASSERT_TRUE(renderer->setImageryLayers(2).ok());
    plane = flatPlane(40'000.0, 8, 0.0f);
    for (auto& v : plane.vertices) v.uv = {v.position.x / 40'000.0f + 0.5f, 0.5f - v.position.y / 40'000.0f};
  }

  // One frame over the plane coloured by a uniform imagery tile of 8-bit sRGB colour `rgb`,
  // from `position` looking along heading north, pitched by `pitchDeg`.
  ColorImage render(Rgb8 rgb, const glm::dvec3& position, double pitchDeg, float detail) {
    std::vector<uint8_t> tile(size_t{kImageryTileSize} * kImageryTileSize * 4);
    for (size_t i = 0; i < tile.size(); i += 4) {
      tile[i] = rgb.r;
      tile[i + 1] = rgb.g;
      tile[i + 2] = rgb.b;
      tile[i + 3] = 255;
    }
    const ImageryUpload upload{1, tile};
    TerrainDraw draw{&plane};
    draw.imageryLayer = 1;
    FrameRequest req;
    const double pitch = glm::radians(pitchDeg);
    req.camera.position = position;
    req.camera.forward = glm::normalize(glm::dvec3(0, std::cos(pitch), std::sin(pitch)));
    req.camera.up = {0, 0, 1};
    req.camera.nearM = 0.5;
    req.cameraHeightMsl = position.z;
    req.readbackColor = true;
    req.terrainDetail = detail;
    req.terrain = {&draw, 1};
    req.imageryUploads = {&upload, 1};
    auto frame = renderer->renderFrame(req);
    EXPECT_TRUE(frame.ok()) << (frame.ok() ? "" : frame.error().message);
    if (!frame.ok()) return {};
    // VEGSTREAM_TEST_FRAMES=DIR: keep every frame as a PNG, to look at.
    if (const char* dir = std::getenv("VEGSTREAM_TEST_FRAMES")) {
      const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
      const std::string name = std::string(info->name()) + "_" + std::to_string(++frames) + ".png";
      EXPECT_TRUE(writePng(std::string(dir) + "/" + name, *frame->color).ok());
    }
    return *frame->color;
  }

  std::unique_ptr<Renderer> renderer;
  terrain::TerrainMesh plane;
  int frames = 0;
};

int channel(const ColorImage& img, uint32_t x, uint32_t y, int c) {
  return img.rgba[(size_t{y} * img.width + x) * 4 + static_cast<size_t>(c)];
}

// Mean over 4 × 4 blocks of rows [y0, y1) of the variance of the green channel inside the block.
double localVariance(const ColorImage& img, uint32_t y0, uint32_t y1) {
  double sum = 0.0;
  int blocks = 0;
  for (uint32_t by = y0; by + 4 <= y1; by += 4)
    for (uint32_t bx = 0; bx + 4 <= img.width; bx += 4) {
      double mean = 0.0, square = 0.0;
      for (uint32_t y = by; y < by + 4; ++y)
        for (uint32_t x = bx; x < bx + 4; ++x) {
          const double g = channel(img, x, y, 1);
          mean += g;
          square += g * g;
        }
      mean /= 16.0;
      sum += square / 16.0 - mean * mean;
      ++blocks;
    }
  return sum / blocks;
}

double meanChannel(const ColorImage& img, uint32_t y0, uint32_t y1, int c) {
  double sum = 0.0;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < img.width; ++x) sum += channel(img, x, y, c);
  return sum / (double(y1 - y0) * img.width);
}

double meanAbsDifference(const ColorImage& a, const ColorImage& b, uint32_t y0, uint32_t y1) {
  double sum = 0.0;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c) sum += std::abs(channel(a, x, y, c) - channel(b, x, y, c));
  return sum / (3.0 * double(y1 - y0) * a.width);
}

const Rgb8 kMeadow{104, 120, 60}, kRedRock{149, 101, 88};

// Close up (3 m above the plane, pitched 35° down: 3–9 m away) a flat, uniformly coloured
// plane is smooth without detail and textured with it, and keeps its average colour.
TEST_F(TerrainDetailTest, PresentCloseUp) {
  const glm::dvec3 eye{13.7, -41.2, 3.0};
  const ColorImage detailed = render(kMeadow, eye, -35.0, 1.0f), plain = render(kMeadow, eye, -35.0, 0.0f);
  ASSERT_EQ(detailed.rgba.size(), size_t{kW} * kH * 4);
  ASSERT_EQ(plain.rgba.size(), detailed.rgba.size());
  const double near = localVariance(detailed, kH / 2, kH), nearPlain = localVariance(plain, kH / 2, kH);
  EXPECT_LT(nearPlain, 0.5);
  EXPECT_GT(near, 12.0) << "grey-level variance inside 4 × 4 blocks close to the camera";
  for (int c = 0; c < 3; ++c) {
    const double a = meanChannel(detailed, kH / 2, kH, c), b = meanChannel(plain, kH / 2, kH, c);
    EXPECT_NEAR(a, b, 0.12 * b + 2.0) << "channel " << c;
  }
}

// 40 m above the plane, pitched 12° down: the bottom rows are 60–90 m away (still detailed),
// the rows just under the horizon (row ≈ 53) beyond 1.5 km, where the terrain must be exactly
// the undetailed imagery.
TEST_F(TerrainDetailTest, AbsentFarAway) {
  const glm::dvec3 eye{13.7, -41.2, 40.0};
  const ColorImage detailed = render(kMeadow, eye, -12.0, 1.0f), plain = render(kMeadow, eye, -12.0, 0.0f);
  ASSERT_EQ(detailed.rgba.size(), size_t{kW} * kH * 4);
  ASSERT_EQ(plain.rgba.size(), detailed.rgba.size());
  for (uint32_t y = 54; y < 58; ++y)
    for (uint32_t x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(channel(detailed, x, y, c), channel(plain, x, y, c), 1) << x << "," << y;
  EXPECT_GT(meanAbsDifference(detailed, plain, 150, kH), 0.5) << "60–90 m away the detail is still there";
}

// From 2.5 km up every visible point is beyond the fade: the whole image is the bare imagery.
TEST_F(TerrainDetailTest, NoneAnywhereFromHighUp) {
  const glm::dvec3 eye{-300.0, 120.0, 2'500.0};
  const ColorImage detailed = render(kRedRock, eye, -50.0, 1.0f), plain = render(kRedRock, eye, -50.0, 0.0f);
  EXPECT_EQ(detailed.rgba, plain.rgba);
}

// The pattern belongs to the ground: moving the camera by one tiling period shows the same
// image, moving it by a fraction of a repeat shows a different one (a pattern tied to the camera
// would look the same after any move over a uniform plane).
TEST_F(TerrainDetailTest, PatternIsAnchoredToTheWorld) {
  const glm::dvec3 eye{5.0, 3.0, 3.0};
  const ColorImage a = render(kMeadow, eye, -60.0, 1.0f);
  const ColorImage period = render(kMeadow, eye + glm::dvec3(kDetailPeriodM, 0.0, 0.0), -60.0, 1.0f);
  const ColorImage moved = render(kMeadow, eye + glm::dvec3(1.3, 0.0, 0.0), -60.0, 1.0f);
  EXPECT_LT(meanAbsDifference(a, period, 0, kH), 0.5);
  EXPECT_GT(meanAbsDifference(a, moved, 0, kH), 4.0);
}

// The colour score picks the detail: meadow green gets grass blades, red sandstone gets rock —
// different patterns at the same place (low correlation of their brightness variations).
TEST_F(TerrainDetailTest, ImageryColourChoosesTheDetail) {
  const glm::dvec3 eye{5.0, 3.0, 3.0};
  const ColorImage grass = render(kMeadow, eye, -60.0, 1.0f), rock = render(kRedRock, eye, -60.0, 1.0f);
  const double mg = meanChannel(grass, 0, kH, 1), mr = meanChannel(rock, 0, kH, 0);
  double cov = 0.0, vg = 0.0, vr = 0.0;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const double g = channel(grass, x, y, 1) - mg, r = channel(rock, x, y, 0) - mr;
      cov += g * r;
      vg += g * g;
      vr += r * r;
    }
  EXPECT_GT(vg, 0.0);
  EXPECT_GT(vr, 0.0);
  EXPECT_LT(std::abs(cov) / std::sqrt(vg * vr), 0.5);
}

}  // namespace
}  // namespace vegstream::render::testing
