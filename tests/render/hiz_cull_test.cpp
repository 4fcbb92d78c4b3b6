// Hi-Z occlusion culling (render/hiz_pass.h, shaders/hiz_*.comp) on lavapipe.
//
// 1. The pyramid: depth rectangles cleared into an odd-sized target (37 × 23, so every level
//    has a cut edge), single-sample and MSAA; every level equals a CPU reduction that keeps
//    the farthest (smallest, reverse-Z) depth of exactly the pixels each texel covers.
// 2. The culling: a grass field from 5 to 122 m north of a camera 2 m up, with a wall across it
//    at 40 m. Behind a tall wall most seed triangles are culled; behind a wall 1 m above the
//    eye, those clear of its foot are. Never a visible one: the frame's depth with culling on is
//    bit for bit the depth with culling off (the plants write depth with a GREATER test, so the
//    stored depth is the nearest fragment's whatever the draw order: a culled group that had a
//    visible sample would change it). Behind a low wall plants peek over its top; they show in
//    the reference and in the culled frame alike. Same inputs, same counts. Validation silent.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "plant_field.h"
#include "render/descriptors.h"
#include "render/frame_slot.h"
#include "render/gpu_resources.h"
#include "render/hiz_pass.h"
#include "render/render_targets.h"

namespace vegstream::render::testing {
namespace {

class HizCullTest : public GpuTest {};

// --- 1. the pyramid -----------------------------------------------------------------------

struct DepthRect {
  int32_t x, y;
  uint32_t w, h;
  float depth;
};

// CPU reference: level 0 = farthest of each 2 × 2 pixel block (cut by the edges), then 2 × 2
// texel blocks of the level below.
std::vector<std::vector<float>> referencePyramid(const std::vector<float>& depth, VkExtent2D e) {
  std::vector<std::vector<float>> out;
  std::vector<float> below = depth;
  uint32_t bw = e.width, bh = e.height;
  for (const HizLevel& l : hizLevels(e)) {
    std::vector<float> level(size_t{l.width} * l.height, 1.0f);
    for (uint32_t y = 0; y < l.height; ++y)
      for (uint32_t x = 0; x < l.width; ++x)
        for (uint32_t dy = 0; dy < 2; ++dy)
          for (uint32_t dx = 0; dx < 2; ++dx) {
            const uint32_t cx = 2 * x + dx, cy = 2 * y + dy;
            if (cx < bw && cy < bh) level[y * l.width + x] = std::min(level[y * l.width + x], below[cy * bw + cx]);
          }
    out.push_back(level);
    below = level;
    bw = l.width;
    bh = l.height;
  }
  return out;
}

TEST_F(HizCullTest, PyramidKeepsTheFarthestDepthOfExactlyTheCoveredPixelsAtEveryLevel) {
  const std::unique_ptr<Context> context = validatedContext();
  ASSERT_TRUE(context);
  const Context& ctx = *context;
  const VkExtent2D extent{37, 23};
  const std::vector<DepthRect> rects = {{0, 0, 37, 23, 0.9f},  {3, 2, 11, 7, 0.2f},  {20, 5, 9, 13, 0.5f},
                                        {36, 0, 1, 23, 0.05f}, {0, 22, 37, 1, 0.3f}, {15, 15, 2, 2, 0.0f}};
  for (const VkSampleCountFlagBits samples : {VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT}) {
    SCOPED_TRACE("samples " + std::to_string(samples));
    RenderTargets targets(ctx, extent, samples);
    DescriptorSetLayout frameLayout = createFrameSetLayout(ctx);  // the cull marks through its binding 10
    HizPass hiz(ctx, frameLayout.get(), targets);
    const std::vector<HizLevel>& levels = hiz.levels();
    ASSERT_EQ(levels.size(), 6u);  // 19×12, 10×6, 5×3, 3×2, 2×1, 1×1
    EXPECT_EQ(levels[0].width, 19u);
    EXPECT_EQ(levels[0].height, 12u);
    const size_t texels = levels.back().offset + 1;
    GpuBuffer host = createBuffer(ctx, texels * sizeof(float), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  MemoryUse::HostReadback, "test pyramid");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
      targets.beginRendering(cmd, RenderTargets::Load::Clear, /*resolve=*/false);
      for (const DepthRect& r : rects) {
        VkClearAttachment a{VK_IMAGE_ASPECT_DEPTH_BIT, 0, {}};
        a.clearValue.depthStencil = {r.depth, 0};
        const VkClearRect cr{{{r.x, r.y}, {r.w, r.h}}, 0, 1};
        vkCmdClearAttachments(cmd, 1, &a, 1, &cr);
      }
      vkCmdEndRendering(cmd);
      hiz.recordBuild(cmd);
      const VkBufferCopy all{0, 0, texels * sizeof(float)};
      vkCmdCopyBuffer(cmd, hiz.pyramid(), host.get(), 1, &all);
      hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });
    std::vector<float> depth(size_t{extent.width} * extent.height, 0.0f);
    for (const DepthRect& r : rects)
      for (uint32_t y = 0; y < r.h; ++y)
        for (uint32_t x = 0; x < r.w; ++x) depth[(r.y + y) * extent.width + r.x + x] = r.depth;
    const auto expected = referencePyramid(depth, extent);
    const auto* got = static_cast<const float*>(host.mapped);
    for (size_t l = 0; l < levels.size(); ++l)
      for (size_t i = 0; i < expected[l].size(); ++i)
        ASSERT_EQ(got[levels[l].offset + i], expected[l][i]) << "level " << l << " texel " << i;
    EXPECT_EQ(got[levels.back().offset], 0.0f) << "the top holds the farthest depth of the frame";
    EXPECT_EQ(expected[0][1 * 19 + 1], 0.2f) << "the test's rectangles reach level 0";
  }
}

// --- 2. the culling -----------------------------------------------------------------------

constexpr double kWallY = 40.0;

// A vertical wall across the view at y = kWallY, from z = −1 to `top`, both faces.
terrain::TerrainMesh wall(float top) {
  terrain::TerrainMesh mesh;
  for (float z : {-1.0f, top})
    for (float x : {-200.0f, 200.0f})
      mesh.vertices.push_back({{x, static_cast<float>(kWallY), z}, {0.0f, -1.0f, 0.0f}, 1500.0f});
  for (auto& v : mesh.vertices) v.uv = fieldUv(v.position.x, v.position.y);
  mesh.indices = {0, 1, 2, 1, 3, 2, 0, 2, 1, 1, 2, 3};
  return mesh;
}

// Seed triangles: 3 m squares from 30 m west to 30 m east and 5 … 122 m north, `plants` each.
std::vector<SeedTriangleGpu> deepField(const glm::dvec3& camera, float plants) {
  return seedTriangles(camera, plants, 120.0);
}

struct Frames {
  FrameResult on, off, bare;  // culling on, off, and no plants at all
  size_t triangles = 0;
};

Frames renderWall(Renderer& r, float wallTop) {
  const std::array<uint8_t, 3> c = referenceColour("grass");
  const std::vector<uint8_t> tile = flatTile(c[0], c[1], c[2]);
  const ImageryUpload upload{0, tile};
  terrain::TerrainMesh plane = flatPlane(kField, 8, 0.0f);
  for (auto& v : plane.vertices) v.uv = fieldUv(v.position.x, v.position.y);
  const terrain::TerrainMesh w = wall(wallTop);
  std::array<TerrainDraw, 2> draws{TerrainDraw{&plane}, TerrainDraw{&w}};
  for (TerrainDraw& d : draws) d.imageryLayer = 0;
  FrameRequest req;
  req.camera.position = {0.0, 0.0, 2.0};
  req.camera.forward = glm::normalize(glm::dvec3(0.0, 1.0, -0.2));
  req.cameraHeightMsl = 2.0;
  req.readbackDepth = true;
  req.readbackColor = true;
  req.terrain = draws;
  req.imageryUploads = {&upload, 1};
  const std::vector<SeedTriangleGpu> seeds = deepField(req.camera.position, 24.0f);
  VegetationRequest plants{seeds, 8, PlantStyle::Plants, {}};
  Frames f;
  f.triangles = seeds.size();
  req.vegetation = &plants;
  auto on = r.renderFrame(req);
  EXPECT_TRUE(on.ok());
  req.imageryUploads = {};
  plants.occlusionCulling = false;
  auto off = r.renderFrame(req);
  EXPECT_TRUE(off.ok());
  req.vegetation = nullptr;
  auto bare = r.renderFrame(req);
  EXPECT_TRUE(bare.ok());
  if (!on.ok() || !off.ok() || !bare.ok()) return f;
  f.on = std::move(*on);
  f.off = std::move(*off);
  f.bare = std::move(*bare);
  return f;
}

// Samples whose depth differs (bitwise) between two frames.
size_t depthDifferences(const DepthImage& a, const DepthImage& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.depth.size(); ++i) n += std::memcmp(&a.depth[i], &b.depth[i], sizeof(float)) != 0;
  return n;
}

// The grass-only catalog: the conifers' 18 m would make every bound tall, and these tests are
// about the boundary between hidden and visible grass. `heightM`: the grass's height range.
vegetation::SpeciesCatalog grassCatalog(vegetation::FloatRange heightM = {0.2f, 0.55f}) {
  vegetation::SpeciesCatalog c = vegetation::defaultSpeciesCatalog();
  std::erase_if(c.species, [](const vegetation::Species& s) { return !s.bare && s.name != "grass"; });
  for (vegetation::Species& s : c.species)
    if (s.name == "grass") s.heightM = heightM;
  return c;
}

void expectNeverCullsAVisibleGroup(const Frames& f, const char* what) {
  SCOPED_TRACE(what);
  ASSERT_TRUE(f.on.vegetation && f.off.vegetation && f.on.depth && f.off.depth && f.bare.depth);
  const VegetationFigures &on = *f.on.vegetation, &off = *f.off.vegetation;
  EXPECT_TRUE(on.occlusionCulling);
  EXPECT_FALSE(off.occlusionCulling);
  EXPECT_EQ(on.cullTested, f.triangles);
  // The plants are there to be lost: they change the depth of many samples without culling.
  EXPECT_GT(depthDifferences(*f.off.depth, *f.bare.depth), 1000u);
  // Culling removes nothing that shows.
  EXPECT_EQ(depthDifferences(*f.on.depth, *f.off.depth), 0u);
  // What the counters say it removed is what is missing from the classify pass's output.
  EXPECT_LE(on.groupsTotal, off.groupsTotal);
  // Plants lost to culling: at most what the counters say were never made (Σ ⌈N⌉ counts them
  // before bare-soil rejection), and some exactly when something was culled.
  ASSERT_GE(off.plantsTotal, on.plantsTotal);
  EXPECT_LE(off.plantsTotal - on.plantsTotal, on.cullPlantsCulled + on.cullGroupPlantsCulled);
  EXPECT_EQ(off.plantsTotal == on.plantsTotal, on.cullCulled == 0 && on.cullGroupsCulled == 0);
  std::printf("%s: %llu of %llu seed triangles culled (%llu clusters, %llu plants); groups %llu → %llu, plants "
              "%llu → %llu\n",
              what, static_cast<unsigned long long>(on.cullCulled), static_cast<unsigned long long>(on.cullTested),
              static_cast<unsigned long long>(on.cullClustersCulled),
              static_cast<unsigned long long>(on.cullPlantsCulled), static_cast<unsigned long long>(off.groupsTotal),
              static_cast<unsigned long long>(on.groupsTotal), static_cast<unsigned long long>(off.plantsTotal),
              static_cast<unsigned long long>(on.plantsTotal));
}

TEST_F(HizCullTest, CullsWhatATallWallHidesAndNothingThatShows) {
  for (int msaa : {4, 1}) {
    SCOPED_TRACE("MSAA " + std::to_string(msaa));
    auto r = makeRenderer(kW, kH, msaa);
    ASSERT_TRUE(r);
    ASSERT_TRUE(r->setImageryLayers(1).ok());
    ASSERT_TRUE(r->setSpeciesCatalog(grassCatalog()).ok());
    const Frames f = renderWall(*r, 60.0f);
    expectNeverCullsAVisibleGroup(f, msaa == 4 ? "tall wall, MSAA 4" : "tall wall, MSAA 1");
    ASSERT_TRUE(f.on.vegetation);
    // Everything from ~2 m behind the wall's foot is hidden: over half of the field.
    EXPECT_GT(f.on.vegetation->cullCulled, f.triangles / 2);
    EXPECT_LT(f.on.vegetation->cullCulled, f.triangles) << "the field in front of the wall stays";
    EXPECT_LT(f.on.vegetation->plantsTotal, f.off.vegetation->plantsTotal / 2);
    // Same inputs, same counts.
    const Frames again = renderWall(*r, 60.0f);
    ASSERT_TRUE(again.on.vegetation);
    EXPECT_EQ(again.on.vegetation->cullCulled, f.on.vegetation->cullCulled);
    EXPECT_EQ(again.on.vegetation->cullClustersCulled, f.on.vegetation->cullClustersCulled);
    EXPECT_EQ(again.on.vegetation->groupsTotal, f.on.vegetation->groupsTotal);
    EXPECT_EQ(again.on.vegetation->plantsTotal, f.on.vegetation->plantsTotal);
  }
}

// The terrain rasterised in compute (render/terrain_raster_pass.h): the pyramid comes from its
// buffer of depth samples, and the plants behind the wall are hidden by the depth attachment those
// samples are written into (shaders/terrain_depth.frag), as by the deferred terrain's own raster.
// The same culling, the same depth read back, and the same picture, plants included.
TEST_F(HizCullTest, TheTerrainRasterisedInComputeCullsAndHidesAsTheDeferredOne) {
  std::array<Frames, 2> frames;
  for (int k = 0; k < 2; ++k) {
    auto r = makeRenderer(kW, kH, 4, k == 0 ? TerrainShading::Deferred : TerrainShading::Compute);
    ASSERT_TRUE(r);
    ASSERT_TRUE(r->setImageryLayers(1).ok());
    ASSERT_TRUE(r->setSpeciesCatalog(grassCatalog()).ok());
    frames[size_t(k)] = renderWall(*r, 60.0f);
  }
  const Frames &deferred = frames[0], &compute = frames[1];
  expectNeverCullsAVisibleGroup(compute, "tall wall, terrain rasterised in compute");
  ASSERT_TRUE(deferred.on.vegetation && compute.on.vegetation);
  // The two depths differ by float rounding only: the same triangles culled, give or take a few
  // on the boundary.
  const double culled = double(deferred.on.vegetation->cullCulled);
  EXPECT_GT(culled, double(deferred.triangles) / 2);
  EXPECT_NEAR(double(compute.on.vegetation->cullCulled), culled, 0.02 * culled);
  // Without culling every plant behind the wall is drawn, and must not show through it.
  for (const FrameResult* f : {&deferred.off, &compute.off, &deferred.bare, &compute.bare}) ASSERT_TRUE(f->color);
  // Grass over ground of the grass's own colour: a plant changes a pixel by a few steps.
  const auto differing = [](const ColorImage& a, const ColorImage& b) { return pixelsOffBy(a, b, 6); };
  const size_t pixels = size_t{kW} * kH;
  EXPECT_GT(differing(*deferred.off.color, *deferred.bare.color), pixels / 100) << "the plants show in front";
  EXPECT_LT(differing(*compute.off.color, *deferred.off.color), pixels / 200);
  EXPECT_LT(differing(*compute.bare.color, *deferred.bare.color), pixels / 500);
  // The depth read back holds the terrain (the wall and the ground), as the deferred one does
  // (sample 0 of each pixel, within float rounding).
  ASSERT_TRUE(compute.bare.depth && deferred.bare.depth);
  ASSERT_EQ(compute.bare.depth->depth.size(), deferred.bare.depth->depth.size());
  size_t terrain = 0, apart = 0;
  for (size_t i = 0; i < pixels; ++i) {
    const float c = compute.bare.depth->depth[i], d = deferred.bare.depth->depth[i];
    terrain += d > 0.0f ? 1 : 0;
    apart += std::abs(c - d) > 1e-5f ? 1 : 0;  // rounding: a few 1e-6
  }
  EXPECT_GT(terrain, pixels / 2);
  EXPECT_LT(apart, pixels / 500);
  // Per sample only where the wall's top meets the sky or the ground behind it: some tiles, far
  // from all of them.
  const uint64_t tiles = uint64_t{(kW + 7) / 8} * ((kH + 7) / 8);
  EXPECT_GT(compute.bare.terrainDepthEdgeTiles, 0u);
  EXPECT_LT(compute.bare.terrainDepthEdgeTiles, tiles / 2);
}

TEST_F(HizCullTest, AWallJustAboveTheEyeHidesTheFieldBehindItsFoot) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  ASSERT_TRUE(r->setSpeciesCatalog(grassCatalog()).ok());
  const Frames f = renderWall(*r, 3.0f);
  expectNeverCullsAVisibleGroup(f, "wall 1 m above the eye");
  ASSERT_TRUE(f.on.vegetation);
  EXPECT_GT(f.on.vegetation->cullCulled, f.triangles / 3);
}

// A wall below the eye, tall grass (1.6 … 2 m) behind it: the ground behind the wall is hidden
// out to ~110 m, but the blades' tips peek over its top. They show in the reference, and the
// culled frame keeps them (the depth check). A bound without the plants' height would cull the
// triangles of those tips (tried: the depth check then fails).
TEST_F(HizCullTest, KeepsThePlantsThatPeekOverALowWall) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  ASSERT_TRUE(r->setSpeciesCatalog(grassCatalog({1.6f, 2.0f})).ok());
  const float top = 1.3f;
  const Frames f = renderWall(*r, top);
  expectNeverCullsAVisibleGroup(f, "wall 0.7 m below the eye");
  ASSERT_TRUE(f.off.depth && f.bare.depth);
  // Samples where plants behind the wall are what shows: without plants they hold the ground
  // beyond the wall's shadow or the sky, with plants something nearer, and farther than the
  // wall (depth below the wall's at its top edge, 40 m away).
  const Camera cam;  // the renderer's default near and far planes
  const double wallDepth = reverseZDepth(cam, kWallY * 0.98);
  size_t peeking = 0;
  for (size_t i = 0; i < f.off.depth->depth.size(); ++i) {
    const float with = f.off.depth->depth[i], without = f.bare.depth->depth[i];
    if (with > without && with < wallDepth) ++peeking;
  }
  EXPECT_GT(peeking, 200u) << "plants behind the wall show over its top";
  std::printf("low wall: %zu samples of plants behind the wall\n", peeking);
}

// Two grasses of the same colour, one 0.2 … 0.55 m, one 3 … 4 m: behind a wall 1 m above the
// eye the short grass is hidden but the tall grass's tips may show, so triangles stay and the
// short grass's groups are dropped per species — and still nothing that shows is lost.
TEST_F(HizCullTest, DropsTheHiddenSpeciesOfATriangleWhoseOtherSpeciesShows) {
  auto r = makeRenderer(kW, kH, 4);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  vegetation::SpeciesCatalog c = grassCatalog();
  const auto grass = std::find_if(c.species.begin(), c.species.end(), [](const auto& s) { return s.name == "grass"; });
  ASSERT_NE(grass, c.species.end());
  vegetation::Species tall = *grass;
  tall.name = "tall grass";
  tall.heightM = {3.0f, 4.0f};
  c.species.insert(grass + 1, tall);
  ASSERT_TRUE(r->setSpeciesCatalog(c).ok());
  const Frames f = renderWall(*r, 3.0f);
  expectNeverCullsAVisibleGroup(f, "two grasses, wall 1 m above the eye");
  ASSERT_TRUE(f.on.vegetation && f.off.vegetation);
  const VegetationFigures &on = *f.on.vegetation, &off = *f.off.vegetation;
  EXPECT_GT(on.cullGroupsCulled, 100u) << "short grass dropped where tall grass may show";
  EXPECT_GT(off.groups[1], 1000u) << "both grasses are picked";
  EXPECT_GT(on.groups[1], 0u) << "the tall grass behind the wall stays";
  std::printf("two grasses: %llu groups dropped per species (%llu plants)\n",
              static_cast<unsigned long long>(on.cullGroupsCulled),
              static_cast<unsigned long long>(on.cullGroupPlantsCulled));
}

}  // namespace
}  // namespace vegstream::render::testing
