// Rendering on the real driver (lavapipe here), at small sizes, checking what a person would
// check rather than comparing bytes with a golden image.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "gpu_test_fixture.h"

namespace vegstream::render::testing {
namespace {

constexpr uint32_t kW = 320, kH = 180;

FrameRequest lookingAt(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up) {
  FrameRequest req;
  req.camera.position = position;
  req.camera.forward = glm::normalize(forward);
  req.camera.up = up;
  req.cameraHeightMsl = position.z;
  req.readbackColor = true;
  req.readbackDepth = true;
  return req;
}

const uint8_t* pixel(const ColorImage& img, uint32_t x, uint32_t y) {
  return &img.rgba[(size_t{y} * img.width + x) * 4];
}
float depthAt(const DepthImage& img, uint32_t x, uint32_t y) { return img.depth[size_t{y} * img.width + x]; }

class RenderTest : public GpuTest {};

// A camera 100 m above a 40 km plane, looking level: sky (depth 0, blue) above the horizon,
// ground (depth > 0) below it, and the horizon on the row the projection predicts.
TEST_F(RenderTest, SkyIsAboveTheHorizonWhereTheCameraSaysItShouldBe) {
  auto r = makeRenderer(kW, kH, 1);
  ASSERT_TRUE(r);
  const terrain::TerrainMesh plane = flatPlane(40'000.0, 8, 0.0f);
  const TerrainDraw draw{&plane};
  const double height = 100.0;
  auto req = lookingAt({0, 0, height}, {0, 1, 0}, {0, 0, 1});
  req.terrain = {&draw, 1};
  auto frame = r->renderFrame(req);
  ASSERT_TRUE(frame.ok()) << frame.error().message;
  const DepthImage& depth = *frame->depth;
  const ColorImage& color = *frame->color;

  // Expected horizon: the plane's far edge (20 km ahead) lies atan(h / 20 km) below level.
  const double tanHalf = std::tan(glm::radians(req.camera.verticalFovDeg) / 2.0);
  const double expectedRow = kH / 2.0 + (kH / 2.0) * (height / 20'000.0) / tanHalf;
  const uint32_t x = kW / 2;
  int horizon = -1;
  for (uint32_t y = 0; y < kH; ++y)
    if (depthAt(depth, x, y) > 0.0f) {
      horizon = static_cast<int>(y);
      break;
    }
  ASSERT_GE(horizon, 0) << "no ground drawn";
  EXPECT_NEAR(horizon, expectedRow, 1.5);
  // Everything above is sky: far-plane depth and blue dominating red.
  for (uint32_t y = 0; y + 1 < static_cast<uint32_t>(horizon); y += 7) {
    EXPECT_EQ(depthAt(depth, x, y), 0.0f) << "row " << y;
    const uint8_t* p = pixel(color, x, y);
    EXPECT_GT(p[2], p[0]) << "sky should be blue at row " << y;
  }
  // Everything below is ground, all the way down.
  for (uint32_t y = static_cast<uint32_t>(horizon); y < kH; y += 5)
    EXPECT_GT(depthAt(depth, x, y), 0.0f) << "row " << y;
  // The sky brightens towards the horizon and is deepest blue at the top.
  EXPECT_LT(pixel(color, x, 0)[0], pixel(color, x, static_cast<uint32_t>(horizon) - 2)[0]);
}

// Pitching the camera up moves the horizon down the image, by the projected angle.
TEST_F(RenderTest, PitchingUpMovesTheHorizonDown) {
  auto r = makeRenderer(kW, kH, 1);
  ASSERT_TRUE(r);
  const terrain::TerrainMesh plane = flatPlane(40'000.0, 8, 0.0f);
  const TerrainDraw draw{&plane};
  const double pitch = glm::radians(10.0);
  auto req = lookingAt({0, 0, 100.0}, {0, std::cos(pitch), std::sin(pitch)}, {0, 0, 1});
  req.terrain = {&draw, 1};
  auto frame = r->renderFrame(req);
  ASSERT_TRUE(frame.ok());
  const double tanHalf = std::tan(glm::radians(req.camera.verticalFovDeg) / 2.0);
  const double below = std::atan(100.0 / 20'000.0) + pitch;
  const double expectedRow = kH / 2.0 + (kH / 2.0) * std::tan(below) / tanHalf;
  int horizon = -1;
  for (uint32_t y = 0; y < kH && horizon < 0; ++y)
    if (depthAt(*frame->depth, kW / 2, y) > 0.0f) horizon = static_cast<int>(y);
  EXPECT_NEAR(horizon, expectedRow, 1.5);
}

// Looking straight down at a plane 250 m below: every pixel is at view distance 250 m, so
// the whole depth buffer reads the reverse-Z depth of 250 m — with and without MSAA.
TEST_F(RenderTest, AKnownPlaneReadsBackTheExpectedDepth) {
  for (int msaa : {1, 4}) {
    auto r = makeRenderer(kW, kH, msaa);
    ASSERT_TRUE(r);
    if (!r->device().supportsMsaa(msaa)) continue;
    const terrain::TerrainMesh plane = flatPlane(10'000.0, 4, 0.0f);
    const TerrainDraw draw{&plane};
    auto req = lookingAt({12.5, -7.25, 250.0}, {0, 0, -1}, {0, 1, 0});
    req.terrain = {&draw, 1};
    auto frame = r->renderFrame(req);
    ASSERT_TRUE(frame.ok());
    const double expected = reverseZDepth(req.camera, 250.0);
    EXPECT_NEAR(expected, 1.0 / 250.0, 1e-5);  // n(f − d)/((f − n)d) ≈ n/d for f ≫ d
    double worst = 0.0;
    for (float d : frame->depth->depth) worst = std::max(worst, std::abs(d - expected));
    EXPECT_LT(worst, 1e-6) << "msaa " << msaa;
  }
}

// A bumpy terrain at MSAA 4: the resolve leaves no black (cleared, never drawn) pixels, its
// colours agree with the single-sampled image on average, and edges do get blended.
TEST_F(RenderTest, MsaaResolveLeavesNoHolesAndAgreesWithSingleSample) {
  terrain::TerrainMesh mesh = flatPlane(8'000.0, 96, 0.0f);
  for (auto& v : mesh.vertices) {
    v.position.z = static_cast<float>(120.0 * std::sin(v.position.x / 300.0) * std::cos(v.position.y / 410.0));
    v.normal =
        glm::normalize(glm::vec3(-0.4f * std::cos(v.position.x / 300.0f) * std::cos(v.position.y / 410.0f),
                                 0.29f * std::sin(v.position.x / 300.0f) * std::sin(v.position.y / 410.0f), 1.0f));
  }
  const TerrainDraw draw{&mesh};
  auto req = lookingAt({0, -3'000, 450.0}, {0, 1, -0.35}, {0, 0, 1});
  req.terrain = {&draw, 1};
  std::vector<ColorImage> images;
  for (int msaa : {1, 4}) {
    auto r = makeRenderer(kW, kH, msaa);
    ASSERT_TRUE(r);
    auto frame = r->renderFrame(req);
    ASSERT_TRUE(frame.ok());
    images.push_back(*frame->color);
  }
  const ColorImage& aa = images[1];
  size_t black = 0, opaque = 0;
  for (size_t i = 0; i < aa.rgba.size(); i += 4) {
    black += (aa.rgba[i] < 3 && aa.rgba[i + 1] < 3 && aa.rgba[i + 2] < 3) ? 1 : 0;
    opaque += aa.rgba[i + 3] == 255 ? 1 : 0;
  }
  EXPECT_EQ(black, 0u);
  EXPECT_EQ(opaque, size_t{kW} * kH);
  double meanDiff = 0.0;
  size_t differing = 0;
  for (size_t i = 0; i < aa.rgba.size(); ++i) {
    const int d = std::abs(int(aa.rgba[i]) - int(images[0].rgba[i]));
    meanDiff += d;
    differing += d > 8 ? 1 : 0;
  }
  meanDiff /= static_cast<double>(aa.rgba.size());
  EXPECT_LT(meanDiff, 2.0);
  EXPECT_GT(differing, 50u) << "MSAA should blend the silhouette edges";
}

// GPU figures come back as plain numbers: a positive frame time, and pipeline statistics that
// count exactly the triangles submitted (terrain + the sky's one; forward shading draws the sky).
TEST_F(RenderTest, TimingsAndPipelineStatisticsCountTheSubmittedWork) {
  auto r = makeRenderer(kW, kH, 1, TerrainShading::Forward);
  ASSERT_TRUE(r);
  const terrain::TerrainMesh mesh = flatPlane(2'000.0, 10, 0.0f);
  const TerrainDraw draw{&mesh};
  FrameRequest req = lookingAt({0, -1'500, 300}, {0, 1, -0.3}, {0, 0, 1});
  req.terrain = {&draw, 1};
  auto frame = r->renderFrame(req);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->terrainTriangles, 200u);
  EXPECT_GT(frame->gpu.frameMs, 0.0);
  ASSERT_EQ(frame->gpu.passes.size(), 4u);
  EXPECT_EQ(frame->gpu.passes[0].pass, "atmosphere");  // the LUTs and the light (render/atmosphere_pass.h)
  EXPECT_EQ(frame->gpu.passes[1].pass, "sky");
  EXPECT_EQ(frame->gpu.passes[2].pass, "terrain");
  EXPECT_EQ(frame->gpu.passes[3].pass, "tonemap");  // exposure and tone map (render/tonemap_pass.h)
  EXPECT_EQ(frame->gpu.perPassMeaningful, !r->device().software);
  ASSERT_TRUE(frame->gpu.statistics.available);
  EXPECT_EQ(frame->gpu.statistics.inputPrimitives, 201u);
  EXPECT_EQ(frame->gpu.statistics.vertexInvocations > 0, true);
  EXPECT_GT(frame->gpu.statistics.fragmentInvocations, uint64_t{kW} * kH / 2);
}

// Two frames in flight, the second with more geometry than the first: each frame's geometry
// lives in its own slot's buffers, and buffers that grow retire the old ones only after the
// frames that use them (the validation layers would report a destroyed buffer in use).
TEST_F(RenderTest, ChangingTheTerrainWhileFramesAreInFlightIsSafe) {
  auto r = makeRenderer(kW / 2, kH / 2, 1);
  ASSERT_TRUE(r);
  const terrain::TerrainMesh small = flatPlane(2'000.0, 4, 0.0f), large = flatPlane(2'000.0, 200, 0.0f);
  const TerrainDraw drawSmall{&small}, drawLarge[2] = {{&large}, {&small}};
  FrameRequest req = lookingAt({0, -1'500, 300}, {0, 1, -0.3}, {0, 0, 1});
  req.readbackColor = req.readbackDepth = false;
  req.terrain = {&drawSmall, 1};
  auto a = r->submitFrame(req);
  ASSERT_TRUE(a.ok());
  req.terrain = {drawLarge, 2};
  auto b = r->submitFrame(req);
  ASSERT_TRUE(b.ok());
  auto fa = r->waitFrame(*a);
  ASSERT_TRUE(fa.ok());
  auto c = r->submitFrame(req);  // the third slot: a third frame in flight
  ASSERT_TRUE(c.ok());
  auto fb = r->waitFrame(*b);
  auto fc = r->waitFrame(*c);
  ASSERT_TRUE(fb.ok() && fc.ok());
  EXPECT_EQ(fa->terrainTriangles, 32u);
  EXPECT_EQ(fb->terrainTriangles, 2u * 200 * 200 + 32u);
  EXPECT_EQ(fc->terrainTriangles, fb->terrainTriangles);
  EXPECT_FALSE(r->waitFrame(*a + 5).ok());
}

// Three frames in flight (render/frame_slots.h), each with its own geometry, waited for in any
// order: every frame's figures are its own; a fourth takes the first one's slot and grows its
// buffers (retired only after that frame); a frame whose slot was taken is no longer waitable.
TEST_F(RenderTest, ThreeFramesInFlightAreWaitedForInAnyOrder) {
  ASSERT_EQ(kFramesInFlight, 3);
  auto r = makeRenderer(kW / 2, kH / 2, 1);
  ASSERT_TRUE(r);
  const terrain::TerrainMesh small = flatPlane(2'000.0, 4, 0.0f), medium = flatPlane(2'000.0, 20, 0.0f),
                             large = flatPlane(2'000.0, 120, 0.0f);
  const TerrainDraw draws[3] = {{&small}, {&medium}, {&large}};
  const uint64_t triangles[3] = {32u, 2u * 20 * 20, 2u * 120 * 120};
  FrameRequest req = lookingAt({0, -1'500, 300}, {0, 1, -0.3}, {0, 0, 1});
  req.readbackColor = req.readbackDepth = false;
  uint64_t index[3] = {};
  for (int k = 0; k < 3; ++k) {
    req.terrain = {&draws[k], 1};
    auto i = r->submitFrame(req);
    ASSERT_TRUE(i.ok());
    index[k] = *i;
  }
  for (int k : {2, 0}) {
    auto f = r->waitFrame(index[k]);
    ASSERT_TRUE(f.ok()) << f.error().message;
    EXPECT_EQ(f->frameIndex, index[k]);
    EXPECT_EQ(f->terrainTriangles, triangles[k]);
  }
  req.terrain = {&draws[2], 1};
  auto fourth = r->submitFrame(req);  // the first frame's slot, whose buffers were small
  ASSERT_TRUE(fourth.ok());
  EXPECT_FALSE(r->waitFrame(index[0]).ok()) << "its slot holds the fourth frame now";
  auto second = r->waitFrame(index[1]);
  auto last = r->waitFrame(*fourth);
  ASSERT_TRUE(second.ok() && last.ok());
  EXPECT_EQ(second->terrainTriangles, triangles[1]);
  EXPECT_EQ(last->terrainTriangles, triangles[2]);
}

// Imagery tiles land in their array layers and colour the draws that name them; a fading tile
// mixes with the layer it replaces by the blend factor.
TEST_F(RenderTest, ImageryLayersColourTheDrawsThatNameThem) {
  auto r = makeRenderer(kW / 2, kH / 2, 1);
  ASSERT_TRUE(r);
  ASSERT_FALSE(r->setImageryLayers(0).ok());
  ASSERT_FALSE(r->setImageryLayers(r->maxImageryLayers() + 1).ok());
  ASSERT_TRUE(r->setImageryLayers(4).ok());
  EXPECT_EQ(r->imageryLayers(), 4u);
  auto tile = [](uint8_t red, uint8_t green) {
    std::vector<uint8_t> rgba(size_t{kImageryTileSize} * kImageryTileSize * 4);
    for (size_t i = 0; i < rgba.size(); i += 4) {
      rgba[i] = red;
      rgba[i + 1] = green;
      rgba[i + 2] = 0;
      rgba[i + 3] = 255;
    }
    return rgba;
  };
  const std::vector<uint8_t> red = tile(255, 0), green = tile(0, 255);
  const ImageryUpload uploads[] = {{2, red}, {3, green}};
  terrain::TerrainMesh plane = flatPlane(4'000.0, 4, 0.0f);
  for (auto& v : plane.vertices) v.uv = {v.position.x / 4'000.0f + 0.5f, 0.5f - v.position.y / 4'000.0f};
  FrameRequest req = lookingAt({0, 0, 500.0}, {0, 0, -1}, {0, 1, 0});
  req.imageryUploads = uploads;
  auto centre = [&](const FrameResult& f) { return pixel(*f.color, f.color->width / 2, f.color->height / 2); };

  TerrainDraw draw{&plane};
  draw.imageryLayer = 2;
  req.terrain = {&draw, 1};
  auto redFrame = r->renderFrame(req);
  ASSERT_TRUE(redFrame.ok());
  EXPECT_GT(centre(*redFrame)[0], 2 * centre(*redFrame)[1]);

  req.imageryUploads = {};
  draw.imageryLayer = 3;
  auto greenFrame = r->renderFrame(req);
  ASSERT_TRUE(greenFrame.ok());
  EXPECT_GT(centre(*greenFrame)[1], 2 * centre(*greenFrame)[0]);

  draw.previousLayer = 2;  // fading from red to green: a quarter of the way
  draw.imageryBlend = 0.25f;
  auto mixed = r->renderFrame(req);
  ASSERT_TRUE(mixed.ok());
  EXPECT_GT(centre(*mixed)[0], centre(*mixed)[1]);
  EXPECT_GT(centre(*mixed)[1], centre(*redFrame)[1] + 20);
}

}  // namespace
}  // namespace vegstream::render::testing
