// Deferred terrain shading (render/terrain_shade_pass.h) against forward shading: the same
// scene through both paths gives the same image up to rounding (the shade pass runs the forward
// fragment shader's own code on the attributes it interpolates itself), the sky included, at
// one and four samples; the deferred frame draws no sky triangle and times the visibility raster
// and the shade as two passes (no sky pass); the
// pieces are drawn front to back.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "gpu_test_fixture.h"
#include "render/terrain_pass.h"

namespace vegstream::render::testing {
namespace {

constexpr uint32_t kW = 160, kH = 90;

FrameRequest lookingAt(const glm::dvec3& position, const glm::dvec3& forward) {
  FrameRequest req;
  req.lighting.exposureEv = 13.0f;  // fixed: frames are compared with each other pixel by pixel
  req.camera.position = position;
  req.camera.forward = glm::normalize(forward);
  req.camera.up = {0, 0, 1};
  req.cameraHeightMsl = position.z;
  req.readbackColor = true;
  return req;
}

// Rolling hills with a checker imagery tile: edges against the sky, slopes for the detail
// textures' triplanar blend, imagery colours for the colour score.
terrain::TerrainMesh hills() {
  terrain::TerrainMesh mesh = flatPlane(3'000.0, 64, 0.0f);
  for (auto& v : mesh.vertices) {
    const float x = v.position.x, y = v.position.y;
    v.position.z = 90.0f * std::sin(x / 170.0f) * std::cos(y / 230.0f);
    v.normal = glm::normalize(glm::vec3(-90.0f / 170.0f * std::cos(x / 170.0f) * std::cos(y / 230.0f),
                                        90.0f / 230.0f * std::sin(x / 170.0f) * std::sin(y / 230.0f), 1.0f));
    v.heightMsl = 1500.0f + v.position.z;
    v.uv = {x / 3'000.0f + 0.5f, 0.5f - y / 3'000.0f};
  }
  return mesh;
}

std::vector<uint8_t> checkerTile() {
  std::vector<uint8_t> rgba(size_t{kImageryTileSize} * kImageryTileSize * 4);
  for (uint32_t y = 0; y < kImageryTileSize; ++y)
    for (uint32_t x = 0; x < kImageryTileSize; ++x) {
      uint8_t* p = &rgba[(size_t{y} * kImageryTileSize + x) * 4];
      const bool green = ((x / 16) + (y / 16)) % 2 == 0;
      p[0] = green ? 70 : 170;
      p[1] = green ? 120 : 120;
      p[2] = green ? 40 : 90;
      p[3] = 255;
    }
  return rgba;
}

struct Comparison {
  double meanAbs = 0.0;
  int maxAbs = 0;
  size_t over2 = 0;  // channel values that differ by more than 2 (of 255)
};

Comparison compare(const ColorImage& a, const ColorImage& b) {
  Comparison c;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    const int d = std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    c.meanAbs += d;
    c.maxAbs = std::max(c.maxAbs, d);
    c.over2 += d > 2 ? 1 : 0;
  }
  c.meanAbs /= static_cast<double>(a.rgba.size());
  return c;
}

class TerrainShadingTest : public GpuTest {
 protected:
  ColorImage render(int msaa, TerrainShading shading, std::span<const TerrainDraw> draws) {
    auto r = makeRenderer(kW, kH, msaa, shading);
    EXPECT_TRUE(r);
    if (!r) return {};
    EXPECT_EQ(r->terrainShading(), shading);
    EXPECT_TRUE(r->setImageryLayers(1).ok());
    const std::vector<uint8_t> tile = checkerTile();
    const ImageryUpload upload{0, tile};
    FrameRequest req = lookingAt({40.0, -1'400.0, 260.0}, {0.1, 1.0, -0.28});
    req.imageryUploads = {&upload, 1};
    req.terrain = draws;
    auto frame = r->renderFrame(req);
    EXPECT_TRUE(frame.ok()) << (frame.ok() ? "" : frame.error().message);
    return frame.ok() ? *frame->color : ColorImage{};
  }
};

TEST_F(TerrainShadingTest, DeferredAndForwardGiveTheSameImageUpToRounding) {
  const terrain::TerrainMesh mesh = hills();
  TerrainDraw draw{&mesh};
  draw.imageryLayer = 0;
  for (int msaa : {1, 4}) {
    const ColorImage forward = render(msaa, TerrainShading::Forward, {&draw, 1});
    const ColorImage deferred = render(msaa, TerrainShading::Deferred, {&draw, 1});
    ASSERT_EQ(forward.rgba.size(), size_t{kW} * kH * 4);
    ASSERT_EQ(deferred.rgba.size(), forward.rgba.size());
    // The scene has sky, lit hills and detail: it is not one flat colour.
    const auto [lo, hi] = std::minmax_element(forward.rgba.begin(), forward.rgba.end());
    EXPECT_GT(*hi - *lo, 100);
    const Comparison c = compare(forward, deferred);
    EXPECT_LT(c.meanAbs, 0.5) << "msaa " << msaa;
    // Rounding (sRGB encoded by the shader instead of the ROP), and derivatives taken per pixel
    // instead of per 2 × 2 quad, move a channel by a step or two; nothing more.
    EXPECT_LT(static_cast<double>(c.over2), 0.002 * static_cast<double>(forward.rgba.size())) << "msaa " << msaa;
    EXPECT_LE(c.maxAbs, 24) << "msaa " << msaa;
  }
}

TEST_F(TerrainShadingTest, WithoutTerrainTheDeferredShadeDrawsTheSky) {
  for (int msaa : {1, 4}) {
    const ColorImage forward = render(msaa, TerrainShading::Forward, {});
    const ColorImage deferred = render(msaa, TerrainShading::Deferred, {});
    ASSERT_EQ(deferred.rgba.size(), size_t{kW} * kH * 4);
    const Comparison c = compare(forward, deferred);
    EXPECT_LE(c.maxAbs, 2) << "msaa " << msaa;
    EXPECT_GT(deferred.rgba[2], 100) << "a blue sky, not a cleared target";
  }
}

TEST_F(TerrainShadingTest, TheDeferredFrameTimesItsTwoTerrainPassesAndDrawsNoSkyTriangle) {
  auto r = makeRenderer(kW, kH, 1, TerrainShading::Deferred);
  ASSERT_TRUE(r);
  const terrain::TerrainMesh mesh = flatPlane(2'000.0, 10, 0.0f);
  const TerrainDraw draw{&mesh};
  FrameRequest req = lookingAt({0, -1'500, 300}, {0, 1, -0.3});
  req.terrain = {&draw, 1};
  auto frame = r->renderFrame(req);
  ASSERT_TRUE(frame.ok());
  EXPECT_EQ(frame->terrainTriangles, 200u);
  ASSERT_EQ(frame->gpu.passes.size(), 4u);
  EXPECT_EQ(frame->gpu.passes[0].pass, "atmosphere");
  EXPECT_EQ(frame->gpu.passes[1].pass, "terrain");  // the visibility raster
  EXPECT_EQ(frame->gpu.passes[2].pass, "terrain shade");
  EXPECT_EQ(frame->gpu.passes[3].pass, "tonemap");
  ASSERT_TRUE(frame->gpu.statistics.available);
  EXPECT_EQ(frame->gpu.statistics.inputPrimitives, 200u);
}

// --- the terrain rasterised in compute (render/terrain_raster_pass.h) ----------------------

TEST_F(TerrainShadingTest, ComputeRasterGivesTheDeferredImage) {
  const terrain::TerrainMesh mesh = hills();
  TerrainDraw draw{&mesh};
  draw.imageryLayer = 0;
  for (int msaa : {1, 4}) {
    const ColorImage deferred = render(msaa, TerrainShading::Deferred, {&draw, 1});
    const ColorImage compute = render(msaa, TerrainShading::Compute, {&draw, 1});
    ASSERT_EQ(compute.rgba.size(), size_t{kW} * kH * 4);
    ASSERT_EQ(deferred.rgba.size(), compute.rgba.size());
    // Deterministic: the lists' order varies with the atomics, the nearest triangle does not.
    EXPECT_EQ(render(msaa, TerrainShading::Compute, {&draw, 1}).rgba, compute.rgba) << "msaa " << msaa;
    // The same triangle ids give the same colours: what may differ is which triangle a sample on
    // a shared edge goes to, and the silhouette against the sky by a sample or so.
    const Comparison c = compare(deferred, compute);
    EXPECT_LT(c.meanAbs, 0.2) << "msaa " << msaa;
    EXPECT_LT(static_cast<double>(c.over2), 0.002 * static_cast<double>(compute.rgba.size())) << "msaa " << msaa;
  }
}

TEST_F(TerrainShadingTest, WithoutTerrainTheComputeRasterDrawsTheSky) {
  for (int msaa : {1, 4}) {
    const ColorImage deferred = render(msaa, TerrainShading::Deferred, {});
    const ColorImage compute = render(msaa, TerrainShading::Compute, {});
    ASSERT_EQ(compute.rgba.size(), size_t{kW} * kH * 4);
    EXPECT_LE(compare(deferred, compute).maxAbs, 1) << "msaa " << msaa;
  }
}

// Pixels whose colour is off by more than 24 in some channel: a crack (sky through the ground)
// or a sample given to a triangle on the wrong side of an edge would be.
size_t farOff(const ColorImage& a, const ColorImage& b) { return pixelsOffBy(a, b, 24); }

// 32 768 small triangles seen from above, every pixel ground: the shared edges leave no sample
// uncovered (the sky would show) and none covered twice; and close over the ground looking ahead,
// where the triangles under the camera are cut by the near plane, the picture is the deferred one.
TEST_F(TerrainShadingTest, TheComputeRasterIsWatertightAndClipsAtTheNearPlane) {
  terrain::TerrainMesh dense = flatPlane(3'000.0, 128, 0.0f);
  for (auto& v : dense.vertices) v.uv = {v.position.x / 3'000.0f + 0.5f, 0.5f - v.position.y / 3'000.0f};
  TerrainDraw draw{&dense};
  draw.imageryLayer = 0;
  const std::vector<uint8_t> tile = checkerTile();
  const ImageryUpload upload{0, tile};
  struct View {
    glm::dvec3 position, forward;
    const char* what;
  };
  for (const View& view : {View{{10.0, -20.0, 900.0}, {0.05, 0.3, -1.0}, "from above"},
                           View{{3.0, -1.0, 0.6}, {0.2, 1.0, -0.02}, "at the near plane"}}) {
    std::array<FrameResult, 2> frames;
    for (int k = 0; k < 2; ++k) {
      auto r = makeRenderer(kW, kH, 4, k == 0 ? TerrainShading::Deferred : TerrainShading::Compute);
      ASSERT_TRUE(r);
      ASSERT_TRUE(r->setImageryLayers(1).ok());
      FrameRequest req = lookingAt(view.position, view.forward);
      req.imageryUploads = {&upload, 1};
      req.terrain = {&draw, 1};
      auto frame = r->renderFrame(req);
      ASSERT_TRUE(frame.ok()) << frame.error().message;
      frames[size_t(k)] = std::move(*frame);
    }
    SCOPED_TRACE(view.what);
    const FrameResult &deferred = frames[0], &compute = frames[1];
    ASSERT_TRUE(deferred.color && compute.color);
    EXPECT_EQ(compute.terrainTriangles, 2u * 128u * 128u);
    EXPECT_GT(compute.terrainRasterTriangles, 0u);
    EXPECT_LT(compute.terrainRasterTriangles, compute.terrainTriangles) << "triangles off screen are culled";
    EXPECT_GE(compute.terrainTileEntries, compute.terrainRasterTriangles);
    EXPECT_EQ(compute.terrainTileEntriesDropped, 0u);
    EXPECT_EQ(deferred.terrainRasterTriangles, 0u) << "only the compute raster counts";
    EXPECT_EQ(farOff(*compute.color, *deferred.color), 0u);
    const Comparison c = compare(*deferred.color, *compute.color);
    EXPECT_LT(c.meanAbs, 0.2);
  }
}

TEST_F(TerrainShadingTest, TheComputeFrameTimesBinningAndRasterAndDrawsNoTriangle) {
  auto r = makeRenderer(kW, kH, 4, TerrainShading::Compute);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->terrainShading(), TerrainShading::Compute);
  const terrain::TerrainMesh mesh = flatPlane(2'000.0, 10, 0.0f);
  const TerrainDraw draw{&mesh};
  FrameRequest req = lookingAt({0, -1'500, 300}, {0, 1, -0.3});
  req.terrain = {&draw, 1};
  for (int frame = 0; frame < 2; ++frame) {  // the second reuses the first's buffers
    auto result = r->renderFrame(req);
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->terrainTriangles, 200u);
    EXPECT_LE(result->terrainRasterTriangles, 200u) << "none clipped by the near plane";
    EXPECT_GT(result->terrainRasterTriangles, 150u) << "a few off screen at the sides";
    ASSERT_EQ(result->gpu.passes.size(), 5u);
    EXPECT_EQ(result->gpu.passes[0].pass, "atmosphere");
    EXPECT_EQ(result->gpu.passes[1].pass, "terrain");        // the binning
    EXPECT_EQ(result->gpu.passes[2].pass, "terrain shade");  // the raster and the shading
    EXPECT_EQ(result->gpu.passes[3].pass, "terrain depth");  // its depth samples into the attachment
    EXPECT_EQ(result->gpu.passes[4].pass, "tonemap");
    ASSERT_TRUE(result->gpu.statistics.available);
    // No triangle of the terrain's; and nothing is drawn over it, so none of its depth goes into
    // the attachment (render/terrain_depth_handover.h).
    EXPECT_EQ(result->terrainDepthTiles, 0u);
    EXPECT_EQ(result->terrainDepthEdgeTiles, 0u);
    EXPECT_EQ(result->gpu.statistics.inputPrimitives, 0u);
  }
}

// Which shading each device gets (no GPU needed): auto rasterises the terrain in compute on a
// GPU, keeps deferred on a CPU rasteriser and falls back to forward where neither runs; an
// explicit choice the device cannot run is one message naming the option, the device and what
// it lacks.
TEST(TerrainShadingChoice, AutoRasterisesInComputeOnAGpuAndDefersOnACpuRasteriser) {
  DeviceInfo gpu;
  gpu.name = "NVIDIA H200";
  gpu.msaaCounts = gpu.storageMsaaCounts = {1, 2, 4, 8};
  gpu.sampleRateShading = true;
  DeviceInfo cpu = gpu;
  cpu.name = "llvmpipe";
  cpu.software = true;
  auto pick = [](TerrainShading asked, const DeviceInfo& d, int msaa) {
    Result<TerrainShading> r = resolveTerrainShading(asked, d, msaa);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return r.ok() ? *r : TerrainShading::Auto;
  };
  EXPECT_EQ(pick(TerrainShading::Auto, gpu, 4), TerrainShading::Compute);
  EXPECT_EQ(pick(TerrainShading::Auto, cpu, 4), TerrainShading::Deferred);
  for (TerrainShading s : {TerrainShading::Forward, TerrainShading::Deferred, TerrainShading::Compute}) {
    EXPECT_EQ(pick(s, gpu, 4), s);
    EXPECT_EQ(pick(s, cpu, 4), s);
  }
  // No per-sample fragment stage: the depth pass cannot write 4 samples, so auto defers; one
  // sample needs none.
  DeviceInfo noSampleRate = gpu;
  noSampleRate.sampleRateShading = false;
  EXPECT_EQ(pick(TerrainShading::Auto, noSampleRate, 4), TerrainShading::Deferred);
  EXPECT_EQ(pick(TerrainShading::Auto, noSampleRate, 1), TerrainShading::Compute);
  Result<TerrainShading> refused = resolveTerrainShading(TerrainShading::Compute, noSampleRate, 4);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(refused.error().message.find("--terrain-shading compute"), std::string::npos);
  EXPECT_NE(refused.error().message.find("NVIDIA H200"), std::string::npos);
  EXPECT_NE(refused.error().message.find("sampleRateShading"), std::string::npos);
  // No storage at 4 samples: forward for auto, a message for deferred and compute.
  DeviceInfo noStorage = gpu;
  noStorage.storageMsaaCounts = {1};
  EXPECT_EQ(pick(TerrainShading::Auto, noStorage, 4), TerrainShading::Forward);
  EXPECT_EQ(pick(TerrainShading::Auto, noStorage, 1), TerrainShading::Compute);
  for (TerrainShading s : {TerrainShading::Deferred, TerrainShading::Compute}) {
    Result<TerrainShading> r = resolveTerrainShading(s, noStorage, 4);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("shaderStorageImageMultisample"), std::string::npos);
  }
}

TEST(TerrainDrawOrder, NearestPiecesComeFirstAndEmptyOnesAreLeftOut) {
  // Four 100 m pieces along y at 0, 1, 2 and 3 km; one without triangles.
  std::vector<terrain::TerrainMesh> meshes(5);
  for (int i = 0; i < 4; ++i) {
    meshes[static_cast<size_t>(i)] = flatPlane(100.0, 2, 0.0f);
    meshes[static_cast<size_t>(i)].origin = {0.0, 1000.0 * i, 0.0};
  }
  std::vector<TerrainDraw> draws;
  for (int i : {2, 0, 4, 3, 1}) draws.push_back(TerrainDraw{&meshes[static_cast<size_t>(i)]});
  // From y = 2.9 km: piece 3 (0.05 km away), 2, then 1, then 0; draw 2 (mesh 4) is empty.
  const std::vector<uint32_t> order = frontToBackOrder(draws, {0.0, 2'900.0, 10.0});
  EXPECT_EQ(order, (std::vector<uint32_t>{3, 0, 4, 1}));
  // A camera inside two boxes' footprints at once keeps their given order (ties are stable).
  meshes[1].origin = meshes[3].origin;
  const std::vector<uint32_t> tied = frontToBackOrder(draws, {0.0, 3'000.0, 0.0});
  EXPECT_EQ(tied[0], 3u);
  EXPECT_EQ(tied[1], 4u);
}

}  // namespace
}  // namespace vegstream::render::testing
