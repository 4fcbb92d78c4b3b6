// Trees on the GPU (issue 20, render/tree_pass.h): the classify pass's levels of detail against
// the rule on the CPU, the impostor's silhouette against the model's at the switch, the 2 % rule
// of the cross-fades, determinism, the budget. Small frames on lavapipe; validation silent.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gpu_test_fixture.h"
#include "lone_tree.h"
#include "render/png_writer.h"
#include "render/shadow_cascades.h"
#include "render/tree_impostors.h"
#include "tests/support/plant_field_scene.h"
#include "tree_frame.h"
#include "vegetation/tree_model.h"

namespace vegstream::render::testing {
namespace {

constexpr float kTreeHeight = 15.0f, kCrown = 5.0f;
constexpr uint32_t kImpostorViewsForTest = kImpostorViews * kImpostorCellPx;

// The default catalog's first tree species of that form, as one model of kTreeHeight.
std::vector<TreeModelSet> oneModel(vegetation::TreeForm form) { return {firstTreeOfForm(form, kTreeHeight, kCrown)}; }

TreeInstanceGpu treeAt(float x, float y, uint32_t seed = 0x12345678u) {
  TreeInstanceGpu t{};
  t.position[0] = x;
  t.position[1] = y;
  t.position[2] = 0.0f;
  t.model = 0;
  t.heightM = kTreeHeight;
  t.crownM = kCrown;
  t.seed = seed;
  t.colour = 0xff000000u;  // no imagery under it: the species' own leaves, full colour
  return t;
}

class TreeRenderTest : public GpuTest {
 protected:
  // One frame of `trees` (uploaded into page 0 …) seen from `camera` looking at `target`.
  FrameResult frame(Renderer& r, const std::vector<TreeInstanceGpu>& trees, const glm::dvec3& camera,
                    const glm::dvec3& target, double fovDeg, const TreeLodDistances& lod, bool fades,
                    bool drawTrees = true, bool cores = true) {
    FrameRequest req;
    req.lighting.exposureEv = 13.0f;  // fixed: frames are compared with each other pixel by pixel
    req.camera.position = camera;
    req.camera.forward = glm::normalize(target - camera);
    req.camera.verticalFovDeg = fovDeg;
    req.camera.nearM = 0.5;
    req.readbackColor = true;
    std::vector<TreePageUpload> uploads;
    std::vector<uint32_t> counts;
    for (size_t first = 0; first < trees.size(); first += kTreePageSize) {
      const auto n = static_cast<uint32_t>(std::min<size_t>(kTreePageSize, trees.size() - first));
      uploads.push_back({static_cast<uint32_t>(counts.size()), n, trees.data() + first});
      counts.push_back(n);
    }
    TreeRequest t;
    t.uploads = uploads;
    t.pageCounts = counts;
    t.lod = lod;
    t.fades = fades;
    t.cores = cores;
    t.cameraEnu[0] = camera.x;
    t.cameraEnu[1] = camera.y;
    t.cameraEnu[2] = camera.z;
    if (drawTrees) req.trees = &t;
    auto result = r.renderFrame(req);
    EXPECT_TRUE(result.ok()) << (result.ok() ? "" : result.error().message);
    return result.ok() ? std::move(*result) : FrameResult{};
  }

    // VEGSTREAM_TREE_TEST_PNG=DIR writes the frames a test looks at (for a person to see them).
  static void dump(const FrameResult& f, const std::string& name) {
    const char* dir = std::getenv("VEGSTREAM_TREE_TEST_PNG");
    if (dir && f.color) (void)writePng(std::string(dir) + "/" + name + ".png", *f.color);
  }

  // Pixels of `a` that differ from the background `bg` by more than 12 in some channel.
  static std::vector<uint8_t> mask(const ColorImage& a, const ColorImage& bg) {
    std::vector<uint8_t> m(size_t{a.width} * a.height, 0);
    for (size_t i = 0; i < m.size(); ++i)
      for (int c = 0; c < 3; ++c)
        if (std::abs(int(a.rgba[i * 4 + c]) - int(bg.rgba[i * 4 + c])) > 12) m[i] = 1;
    return m;
  }

  // A row of `count` trees 7 m apart (each with its own seed: yaw, lean, branch angles) seen from
  // `distance` m, in a narrow view whose pixels are a 1080-line, 55° view's: the background, every
  // tree as its full model, every tree as its impostor.
  struct RowFrames {
    FrameResult bg, model, impostor;
  };
  RowFrames rowOfTrees(Renderer& r, int count, double distance) {
    std::vector<TreeInstanceGpu> trees;
    for (int i = 0; i < count; ++i)
      trees.push_back(treeAt(float(i - 0.5 * (count - 1)) * 7.0f, 0.0f, 0x9e3779b9u * uint32_t(i + 1)));
    TreeLodDistances full, impostor;
    full.fullHeights = full.reducedHeights = 1e6f;
    full.horizonM = impostor.horizonM = 1e5f;
    impostor.fullHeights = 1e-4f;
    impostor.reducedHeights = 2e-4f;
    const glm::dvec3 camera{0.0, -distance, 0.5 * kTreeHeight}, target{0.0, 0.0, 0.5 * kTreeHeight};
    const double pixelsPerRadian = 540.0 / std::tan(27.5 * 3.14159265358979 / 180.0);  // 1080p, 55°
    const double fov = 2.0 * std::atan(48.0 / pixelsPerRadian) * 180.0 / 3.14159265358979;
    return {frame(r, trees, camera, target, fov, full, false, /*drawTrees=*/false),
            frame(r, trees, camera, target, fov, full, false), frame(r, trees, camera, target, fov, impostor, false)};
  }
};

// The classify pass puts each tree at the level the rule gives for its distance in tree heights
// (fades off: one level each), and counts what it appended.
TEST_F(TreeRenderTest, LevelsOfDetailFollowTheDistanceRule) {
  auto r = makeRenderer(96, 64, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setTreeModels(oneModel(vegetation::TreeForm::Conifer)).ok());
  ASSERT_GT(r->treePageCapacity(), 0u);
  // 600 trees on a line straight ahead, 2 … 2 400 m away: every level, and some past the horizon.
  std::vector<TreeInstanceGpu> trees;
  for (int i = 0; i < 600; ++i) trees.push_back(treeAt(0.0f, 2.0f + 4.0f * float(i), uint32_t(i) * 2654435761u));
  // The distances scale with the view's pixels per radian (treeLodScale): chosen so that this
  // 64-line, 60° view switches at 6 and 20 tree heights.
  const float scale = treeLodScale(64.0, 60.0);
  TreeLodDistances lod;
  lod.fullHeights = 6.0f / scale;
  lod.reducedHeights = 20.0f / scale;
  lod.impostorEndHeights = 1e6f;  // the horizon ends them here (the end by size: its own test)
  lod.horizonM = 2000.0f;
  const FrameResult f = frame(*r, trees, {0.0, -1.0, 40.0}, {0.0, 1000.0, 0.0}, 60.0, lod, /*fades=*/false);
  ASSERT_TRUE(f.trees && f.trees->gpuCounts);
  uint32_t full = 0, reduced = 0, impostor = 0;
  for (const TreeInstanceGpu& t : trees) {
    const double d = glm::length(glm::dvec3(t.position[0], t.position[1], t.position[2]) - glm::dvec3(0.0, -1.0, 40.0));
    if (d >= lod.horizonM) continue;
    const double h = d / kTreeHeight;
    (h < 6.0 ? full : h < 20.0 ? reduced : impostor)++;
  }
  std::printf("full %u / %u, reduced %u / %u, impostor %u / %u (GPU / rule)\n", f.trees->full, full, f.trees->reduced,
              reduced, f.trees->impostor, impostor);
  EXPECT_EQ(f.trees->instances, 600u);
  // Trees near the view's edges may be culled: the frustum test is a sphere against the planes.
  EXPECT_NEAR(double(f.trees->full), double(full), 2.0);
  EXPECT_EQ(f.trees->reduced, reduced);
  EXPECT_EQ(f.trees->impostor, impostor);
  EXPECT_EQ(f.trees->dropped, 0u);
}

// At the switch distance the octahedral impostor covers the same pixels as the full model within
// 5 %, for both forms. The trees are drawn at the size they have at the switch in a 1080p view of
// 55° (about 50 pixels tall): a narrow view of a row of 12 trees (each with its own seed: yaw,
// lean, branch angles) on a small frame.
TEST_F(TreeRenderTest, ImpostorSilhouetteMatchesTheModelAtTheSwitch) {
  for (auto form : {vegetation::TreeForm::Conifer, vegetation::TreeForm::Broadleaf}) {
    auto r = makeRenderer(320, 96, 1);
    ASSERT_TRUE(r);
    ASSERT_TRUE(r->setTreeModels(oneModel(form)).ok());
    const RowFrames row = rowOfTrees(*r, 12, TreeLodDistances{}.reducedHeights * kTreeHeight);  // at the switch
    const FrameResult &bg = row.bg, &a = row.model, &b = row.impostor;
    ASSERT_TRUE(bg.color && a.color && b.color);
    const std::string tag = form == vegetation::TreeForm::Conifer ? "conifer" : "broadleaf";
    dump(a, "silhouette-" + tag + "-model");
    dump(b, "silhouette-" + tag + "-impostor");
    if (std::getenv("VEGSTREAM_TREE_TEST_PNG")) {
      auto atlas = r->readTreeImpostor(0);
      ASSERT_TRUE(atlas.ok());
      const uint32_t side = kImpostorViewsForTest;
      (void)writePng(std::string(std::getenv("VEGSTREAM_TREE_TEST_PNG")) + "/atlas-" + tag + ".png",
                     ColorImage{side, side, *atlas});
    }
    ASSERT_EQ(a.trees->full, 12u);
    ASSERT_EQ(b.trees->impostor, 12u);
    const auto ma = mask(*a.color, *bg.color), mb = mask(*b.color, *bg.color);
    size_t na = 0, nb = 0, both = 0;
    for (size_t i = 0; i < ma.size(); ++i) {
      na += ma[i];
      nb += mb[i];
      both += ma[i] & mb[i];
    }
    const double coverage = std::abs(double(nb) - double(na)) / double(na);
    const double symmetric = double(na + nb - 2 * both) / double(na);
    std::printf("%s: model %zu px, impostor %zu px: coverage differs by %.1f %%, %.1f %% of the pixels differ\n",
                form == vegetation::TreeForm::Conifer ? "conifer" : "broadleaf", na, nb, 100.0 * coverage,
                100.0 * symmetric);
    EXPECT_GT(na, 2000u);
    EXPECT_LT(coverage, 0.05);
  }
}

// The atlases' mip levels (render/tree_impostors.h): each a 2 × 2 box of the level above that
// never crosses a cell's edge, so every cell keeps its coverage (mean alpha) at every level, to
// the 8-bit rounding of each blit; a blit across cells, or no levels at all, moves it.
TEST_F(TreeRenderTest, ImpostorMipLevelsKeepEveryCellsCoverage) {
  auto r = makeRenderer(64, 64, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setTreeModels(oneModel(vegetation::TreeForm::Conifer)).ok());
  const auto cellMeans = [&](uint32_t level) {
    const auto atlas = r->readTreeImpostor(0, level);
    EXPECT_TRUE(atlas.ok());
    const uint32_t side = kImpostorViewsForTest >> level, cell = kImpostorCellPx >> level;
    std::vector<double> mean(kImpostorViews * kImpostorViews, 0.0);
    if (!atlas.ok() || atlas->size() != size_t{side} * side * 4) return mean;
    for (uint32_t y = 0; y < side; ++y)
      for (uint32_t x = 0; x < side; ++x)
        mean[(y / cell) * kImpostorViews + x / cell] += (*atlas)[(size_t{y} * side + x) * 4 + 3] / 255.0;
    for (double& m : mean) m /= double(cell) * cell;
    return mean;
  };
  const std::vector<double> top = cellMeans(0);
  for (double m : top) EXPECT_GT(m, 0.02) << "every view of the tree covers part of its cell";
  for (uint32_t level = 1; level < kImpostorMipLevels; ++level) {
    const std::vector<double> m = cellMeans(level);
    for (size_t c = 0; c < m.size(); ++c)
      EXPECT_NEAR(m[c], top[c], double(level) * 1.0 / 255.0) << "level " << level << ", cell " << c;
  }
  EXPECT_FALSE(r->readTreeImpostor(0, kImpostorMipLevels).ok());
}

// Far beyond the switch (trees a quarter of their switch size, about 12 pixels tall: the atlas
// read two levels down), a row of impostors still covers about what the full models cover there:
// thin foliage keeps its coverage at distance (issue 41 item 5).
TEST_F(TreeRenderTest, FarImpostorsKeepTheModelsCoverage) {
  for (auto form : {vegetation::TreeForm::Conifer, vegetation::TreeForm::Broadleaf}) {
    auto r = makeRenderer(320, 96, 4);
    ASSERT_TRUE(r);
    ASSERT_TRUE(r->setTreeModels(oneModel(form)).ok());
    const RowFrames row = rowOfTrees(*r, 24, 4.0 * TreeLodDistances{}.reducedHeights * kTreeHeight);
    const FrameResult &bg = row.bg, &a = row.model, &b = row.impostor;
    ASSERT_TRUE(bg.color && a.color && b.color);
    ASSERT_EQ(b.trees->impostor, 24u);
    // Coverage as the share of each pixel's colour moved from the background (MSAA 4 resolves).
    const auto covered = [&](const ColorImage& img) {
      double sum = 0.0;
      for (size_t i = 0; i + 3 < img.rgba.size(); i += 4) {
        int diff = 0;
        for (size_t c = 0; c < 3; ++c) diff = std::max(diff, std::abs(int(img.rgba[i + c]) - int(bg.color->rgba[i + c])));
        sum += diff > 12 ? 1.0 : 0.0;
      }
      return sum;
    };
    const double na = covered(*a.color), nb = covered(*b.color);
    std::printf("%s at 4x the switch: model %.0f px, impostor %.0f px (%.1f %%)\n",
                form == vegetation::TreeForm::Conifer ? "conifer" : "broadleaf", na, nb, 100.0 * (nb - na) / na);
    EXPECT_GT(na, 300.0);
    EXPECT_NEAR(nb / na, 1.0, 0.15);
  }
}

// The crowns' opaque cores (vegetation/tree_core.h), drawn first: seen from the side, close, at
// the full model, they show between the cards (pixels of the crowns change, darker: foliage in
// shade) and only inside each crown's outline (each row between the cards' leftmost and rightmost
// pixel): the trees cover no more of the frame than the cards and bark did. Both forms, a row of
// five trees, cores on and off.
TEST_F(TreeRenderTest, CrownCoresShowBetweenTheCardsOnlyInsideTheOutline) {
  for (auto form : {vegetation::TreeForm::Conifer, vegetation::TreeForm::Broadleaf}) {
    auto r = makeRenderer(320, 128, 4);
    ASSERT_TRUE(r);
    ASSERT_TRUE(r->setTreeModels(oneModel(form)).ok());
    std::vector<TreeInstanceGpu> trees;
    for (int i = 0; i < 5; ++i) trees.push_back(treeAt(float(i - 2) * 9.0f, 0.0f, 0x9e3779b9u * uint32_t(i + 1)));
    TreeLodDistances full;
    full.fullHeights = full.reducedHeights = 1e6f;
    full.horizonM = 1e5f;
    const glm::dvec3 camera{0.0, -40.0, 0.5 * kTreeHeight}, target{0.0, 0.0, 0.5 * kTreeHeight};
    const FrameResult bg = frame(*r, trees, camera, target, 30.0, full, false, /*drawTrees=*/false);
    const FrameResult on = frame(*r, trees, camera, target, 30.0, full, false, true, /*cores=*/true);
    const FrameResult off = frame(*r, trees, camera, target, 30.0, full, false, true, /*cores=*/false);
    ASSERT_TRUE(bg.color && on.color && off.color);
    const std::string tag = form == vegetation::TreeForm::Conifer ? "conifer" : "broadleaf";
    dump(on, "cores-on-" + tag);
    dump(off, "cores-off-" + tag);
    const auto mOn = mask(*on.color, *bg.color), mOff = mask(*off.color, *bg.color), changed = mask(*on.color, *off.color);
    // Per tree (the frame split into five columns), each row's outline from the cards and bark.
    const uint32_t w = on.color->width, h = on.color->height, column = w / 5;
    size_t cards = 0, inside = 0, outside = 0, darker = 0;
    for (uint32_t t = 0; t < 5; ++t)
      for (uint32_t y = 0; y < h; ++y) {
        uint32_t lo = w, hi = 0;
        for (uint32_t x = t * column; x < (t + 1) * column; ++x)
          if (mOff[size_t(y) * w + x]) lo = std::min(lo, x), hi = x, ++cards;
        for (uint32_t x = t * column; x < (t + 1) * column; ++x) {
          const size_t i = size_t(y) * w + x;
          if (!changed[i]) continue;
          if (x < lo || x > hi) {
            outside += mOn[i];  // drawn where neither cards nor bark were
            continue;
          }
          ++inside;
          const uint8_t* a = &on.color->rgba[i * 4];
          const uint8_t* b = &off.color->rgba[i * 4];
          darker += a[0] + a[1] + a[2] < b[0] + b[1] + b[2] ? 1 : 0;
        }
      }
    std::printf("%s: cards and bark %zu px; the cores change %zu inside the outline (%zu of them darker), draw %zu "
                "outside\n",
                tag.c_str(), cards, inside, darker, outside);
    EXPECT_GT(cards, 3000u);
    EXPECT_GT(inside * 20, cards) << "the cores show between the cards";
    EXPECT_GT(darker * 10, inside * 7) << "as foliage in shade";
    // (A core's antialiased edge may add a pixel where a row of cards is narrow: 1.4 % for the conifer.)
    EXPECT_LT(outside * 50, cards) << "the cores stay inside the crowns";
  }
}

// The 2 % rule along a slow flight: the tree's distance in tree heights steps by 0.15 % a frame
// (9 m/s at 100 m and 60 fps)
// through each switch (full → reduced, reduced → impostor, impostor → the terrain's own colour);
// the camera is held still and the switch distances move instead, so every change between frames
// is the level of detail's own. With the fades no frame changes more than 2 % of the tree's
// pixels; without them the switches are visible.
TEST_F(TreeRenderTest, CrossFadesKeepTheTwoPercentRule) {
  auto r = makeRenderer(128, 128, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setTreeModels(oneModel(vegetation::TreeForm::Broadleaf)).ok());
  const std::vector<TreeInstanceGpu> trees = {treeAt(0.0f, 0.0f)};
  const double d = 60.0;  // the camera's distance; the tree is d / h = 4 heights away
  const glm::dvec3 camera{0.0, -d, 0.5 * kTreeHeight}, target{0.0, 0.0, 0.5 * kTreeHeight};
  const double fov = 2.0 * std::atan(0.75 * kTreeHeight / d) * 180.0 / 3.14159265358979;
  TreeLodDistances base;
  base.horizonM = 1e5f;
  base.reducedHeights = 1e6f;  // each switch on its own: the reduced model until switch 1 moves it
  const FrameResult bg = frame(*r, trees, camera, target, fov, base, false, false);
  const FrameResult whole = frame(*r, trees, camera, target, fov, base, false);
  ASSERT_TRUE(bg.color && whole.color);
  size_t treePixels = 0;
  for (uint8_t m : mask(*whole.color, *bg.color)) treePixels += m;
  dump(whole, "fade-whole");
  ASSERT_GT(treePixels, 600u);  // enough for 2 % to be a dozen pixels
  const float at = float(d / kTreeHeight) / treeLodScale(128.0, fov);  // in the renderer's scaled heights
  double worst[2] = {0.0, 0.0};
  for (int fades = 0; fades < 2; ++fades) {
    for (int sw = 0; sw < 3; ++sw) {
      std::vector<uint8_t> before;
      // Without the fades every 5th frame of the flight is enough to see the switches.
      for (int step = -3; step <= 103; step += fades == 1 ? 1 : 5) {
        // The switch at distance `at` · s: s from 1 + share (not started) down past 1 − … (done).
        const float s = 1.0f / (1.0f - base.fadeShare * (float(step) / 100.0f));
        TreeLodDistances lod = base;
        if (sw == 0) lod.fullHeights = at * s;
        if (sw == 1) lod.fullHeights = 1e-4f, lod.reducedHeights = at * s;
        if (sw == 2) lod.fullHeights = 1e-4f, lod.reducedHeights = 2e-4f, lod.horizonM = float(d) * s;
        const FrameResult f = frame(*r, trees, camera, target, fov, lod, fades == 1);
        ASSERT_TRUE(f.color);
        std::vector<uint8_t> now = f.color->rgba;
        if (!before.empty()) {  // pixels that change, as a share of the whole tree's pixels
          size_t changed = 0;
          for (size_t i = 0; i + 3 < now.size(); i += 4) {
            bool differs = false;
            for (int c = 0; c < 3; ++c) differs |= std::abs(int(now[i + c]) - int(before[i + c])) > 24;
            changed += differs ? 1 : 0;
          }
          const double share = double(changed) / double(treePixels);
          if (share > worst[fades]) std::printf("  fades %d switch %d step %d: %.2f %%\n", fades, sw, step, 100.0 * share);
          worst[fades] = std::max(worst[fades], share);
        }
        before = std::move(now);
      }
    }
  }
  std::printf("tree of %zu pixels; largest change between frames: %.2f %% of them with fades, %.2f %% without\n",
              treePixels, 100.0 * worst[1], 100.0 * worst[0]);
  EXPECT_LE(worst[1], 0.02);
  EXPECT_GT(worst[0], 0.10) << "without the fades the check must see the switches";
}

// A known occluder over a flat plane darkens the expected pixels: one tree, the sun low in the
// west; the ground pixels the sun shadow darkens (against the same frame with the trees'
// shadows off, the tree itself left out) are those whose ray towards the sun passes through the
// tree's crown cylinder, and the ground under the crown's centre, seen along the sun, is dark.
TEST_F(TreeRenderTest, SunShadowDarkensTheGroundBehindTheTree) {
  auto r = makeRenderer(160, 120, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setImageryLayers(1).ok());
  ASSERT_TRUE(r->setTreeModels(oneModel(vegetation::TreeForm::Conifer)).ok());
  const std::vector<uint8_t> tile = flatTile(150, 140, 120);
  terrain::TerrainMesh plane = flatPlane(kField, 8, 0.0f);
  for (auto& v : plane.vertices) v.uv = fieldUv(v.position.x, v.position.y);
  TerrainDraw draw{&plane};
  draw.imageryLayer = 0;
  const ImageryUpload upload{0, tile};
  const glm::dvec3 sun = glm::normalize(glm::dvec3(-1.0, 0.0, 0.9));  // towards the sun: west, 42° up
  const std::vector<TreeInstanceGpu> trees = {treeAt(0.0f, 0.0f)};
  const glm::dvec3 camera{8.0, -30.0, 28.0};
  Camera cam;
  cam.position = camera;
  cam.forward = glm::normalize(glm::dvec3(9.0, 2.0, 0.0) - camera);
  cam.verticalFovDeg = 60.0;
  auto render = [&](bool withTrees, bool shadows, bool upload0) {
    return renderTreeFrame(*r, cam, sun, draw, upload0 ? &upload : nullptr, trees, withTrees, shadows);
  };
  const FrameResult bare = render(false, false, true);
  const FrameResult lit = render(true, false, false);
  const FrameResult shaded = render(true, true, false);
  ASSERT_TRUE(bare.color && lit.color && shaded.color && shaded.depth);
  dump(lit, "shadow-off");
  dump(shaded, "shadow-on");
  const auto treePixels = mask(*lit.color, *bare.color);
  // Back from a pixel to the ground: the depth's camera-relative point.
  const double aspect = 160.0 / 120.0;
  const glm::dmat4 inv = glm::inverse(projection(cam, aspect) * viewRotation(cam));
  size_t darkened = 0, expected = 0, ground = 0;
  const double crownR = 0.5 * kCrown + 0.6;
  for (uint32_t y = 0; y < 120; ++y)
    for (uint32_t x = 0; x < 160; ++x) {
      const size_t i = size_t{y} * 160 + x;
      if (treePixels[i]) continue;
      const float depth = shaded.depth->depth[i];
      if (depth <= 0.0f) continue;  // sky
      const glm::dvec4 clip((x + 0.5) / 80.0 - 1.0, (y + 0.5) / 60.0 - 1.0, depth, 1.0);
      glm::dvec4 p = inv * clip;
      const glm::dvec3 world = glm::dvec3(p) / p.w + camera;
      if (std::abs(world.z) > 0.3) continue;  // not the ground
      ++ground;
      const double before = lit.color->rgba[i * 4 + 1], after = shaded.color->rgba[i * 4 + 1];
      if (after > 0.75 * before) continue;
      ++darkened;
      // Does the ray towards the sun pass through the crown's cylinder (up to the tree's height)?
      const double t = -glm::dot(glm::dvec2(world), glm::dvec2(sun)) / glm::dot(glm::dvec2(sun), glm::dvec2(sun));
      const glm::dvec3 q = world + sun * std::max(t, 0.0);
      if (glm::length(glm::dvec2(q)) < crownR && q.z < kTreeHeight + 0.5) ++expected;
    }
  std::printf("%zu ground pixels, %zu darkened by the tree's shadow, %zu of them where the crown's shadow falls\n",
              ground, darkened, expected);
  EXPECT_GT(darkened, 50u);
  EXPECT_GE(double(expected), 0.95 * double(darkened));
}

// Each sun cascade draws only the trees whose sphere reaches its box (the classify's test), not
// every tree three times: trees up to 2.6 km ahead, the counts against the same box test on the
// CPU (a metre either side for rounding), and the far trees cast into no cascade.
TEST_F(TreeRenderTest, EachShadowCascadeDrawsOnlyTheCastersItsBoxReaches) {
  auto r = makeRenderer(160, 90, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setTreeModels(oneModel(vegetation::TreeForm::Conifer)).ok());
  std::vector<TreeInstanceGpu> trees;
  for (int i = 0; i < 240; ++i) {  // 5 m … 2.6 km ahead, spread across the view
    const float y = 5.0f * std::pow(1.0265f, float(i));
    trees.push_back(treeAt(float((i * 37) % 21 - 10) * 0.02f * y, y, 100u + uint32_t(i)));
  }
  ASSERT_GT(trees.back().position[1], 2500.0f);
  const glm::dvec3 camera{0.0, -10.0, 12.0}, target{0.0, 60.0, 4.0};
  TreeLodDistances lod;
  lod.impostorEndHeights /= treeLodScale(90.0, 50.0);  // every tree drawn, as in a 1080-line frame
  FrameRequest req;
  req.lighting.exposureEv = 13.0f;  // fixed: frames are compared with each other pixel by pixel
  req.camera.position = camera;
  req.camera.forward = glm::normalize(target - camera);
  req.camera.verticalFovDeg = 50.0;
  req.camera.nearM = 0.5;
  const std::vector<TreePageUpload> uploads = {{0, 240, trees.data()}};
  const std::vector<uint32_t> counts = {240};
  TreeRequest t;
  t.uploads = uploads;
  t.pageCounts = counts;
  t.lod = lod;
  t.cameraEnu[0] = camera.x, t.cameraEnu[1] = camera.y, t.cameraEnu[2] = camera.z;
  req.trees = &t;
  auto f = r->renderFrame(req);
  ASSERT_TRUE(f.ok()) << f.error().message;
  ASSERT_TRUE(f->trees);

  // The same boxes on the CPU (the renderer's settings: 1024² maps).
  ShadowSettings settings;
  const ShadowCascades boxes = shadowCascades(req.camera, 160.0 / 90.0, req.lighting.sunDirection, settings);
  std::array<uint32_t, kTreeShadowCascades> surely{}, maybe{};
  uint32_t inNone = 0;
  for (const TreeInstanceGpu& tree : trees) {
    const glm::vec3 centre = glm::vec3(tree.position[0], tree.position[1], tree.position[2] + 0.5f * kTreeHeight) -
                             glm::vec3(camera);
    const float radius = 0.7f * std::max(kTreeHeight, kCrown);
    bool any = false;
    for (uint32_t c = 0; c < kTreeShadowCascades; ++c) {
      const glm::mat4& m = boxes.matrices[c];
      const glm::vec4 p = m * glm::vec4(centre, 1.0f);
      const glm::vec3 scale(glm::length(glm::vec3(m[0][0], m[1][0], m[2][0])),
                            glm::length(glm::vec3(m[0][1], m[1][1], m[2][1])),
                            glm::length(glm::vec3(m[0][2], m[1][2], m[2][2])));
      auto inside = [&](float grow) {
        const glm::vec3 e = grow * scale;
        return std::abs(p.x) <= 1.0f + e.x && std::abs(p.y) <= 1.0f + e.y && p.z >= -e.z && p.z <= 1.0f + e.z;
      };
      surely[c] += inside(radius - 1.0f) ? 1u : 0u;
      maybe[c] += inside(radius + 1.0f) ? 1u : 0u;
      any = any || inside(radius + 1.0f);
    }
    inNone += any ? 0u : 1u;
  }
  const TreeFigures& fig = *f->trees;
  EXPECT_GE(fig.full + fig.reduced + fig.impostor, 240u) << "every tree is drawn";
  EXPECT_EQ(fig.dropped, 0u);
  for (uint32_t c = 0; c < kTreeShadowCascades; ++c) {
    std::printf("cascade %u: %u casters (the CPU's box test: %u … %u)\n", c, fig.shadowCasters[c], surely[c], maybe[c]);
    EXPECT_GE(fig.shadowCasters[c], surely[c]);
    EXPECT_LE(fig.shadowCasters[c], maybe[c]);
    EXPECT_GT(fig.shadowCasters[c], 0u);
  }
  EXPECT_LT(fig.shadowCasters[0], fig.shadowCasters[1]);
  EXPECT_LT(fig.shadowCasters[1], fig.shadowCasters[2]);
  EXPECT_GT(inNone, 20u) << "the far trees are beyond every cascade";
  EXPECT_LE(fig.shadowCasters[2], 240u - inNone);

  // The next frame, the camera still, draws one cascade (render/shadow_refresh.h): the classify
  // casts into that one alone, the same trees as before, and into none of the kept ones.
  auto next = r->renderFrame(req);
  ASSERT_TRUE(next.ok() && next->trees);
  uint32_t castInto = 0;
  for (uint32_t c = 0; c < kTreeShadowCascades; ++c) {
    if (next->trees->shadowCasters[c] == 0) continue;
    ++castInto;
    EXPECT_EQ(next->trees->shadowCasters[c], fig.shadowCasters[c]) << "cascade " << c;
  }
  EXPECT_EQ(castInto, 1u);

  // Without shadows nothing is cast.
  t.shadows = false;
  auto g = r->renderFrame(req);
  ASSERT_TRUE(g.ok() && g->trees);
  for (uint32_t c = 0; c < kTreeShadowCascades; ++c) EXPECT_EQ(g->trees->shadowCasters[c], 0u);
}

// The same trees give the same image twice; a budget too small for the models is refused naming
// the option.
TEST_F(TreeRenderTest, SameTreesSameImageAndBudgetRefusal) {
  auto r = makeRenderer(96, 64, 1);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->setTreeModels(oneModel(vegetation::TreeForm::Conifer)).ok());
  std::vector<TreeInstanceGpu> trees;
  for (int i = 0; i < 40; ++i) trees.push_back(treeAt(float(i % 8) * 6.0f - 21.0f, 10.0f + float(i / 8) * 12.0f, i));
  TreeLodDistances lod;  // at 1080-line distances on this small frame: every level shows
  lod.fullHeights /= treeLodScale(64.0, 55.0);
  lod.reducedHeights /= treeLodScale(64.0, 55.0);
  const FrameResult a = frame(*r, trees, {0.0, -10.0, 12.0}, {0.0, 40.0, 4.0}, 55.0, lod, true);
  const FrameResult b = frame(*r, trees, {0.0, -10.0, 12.0}, {0.0, 40.0, 4.0}, 55.0, lod, true);
  ASSERT_TRUE(a.color && b.color);
  EXPECT_EQ(a.color->rgba, b.color->rgba);
  EXPECT_GT(a.trees->full, 0u);  // every level shows
  EXPECT_GT(a.trees->reduced, 0u);
  EXPECT_GT(a.trees->impostor, 0u);
  EXPECT_GT(a.trees->full + a.trees->reduced, 20u);

  RendererOptions o = options(32, 32, 1);
  o.treeBudgetBytes = 1 << 20;  // 1 MiB: not even the atlas
  auto small = Renderer::create(o);
  ASSERT_TRUE(small.ok());
  const Status s = (*small)->setTreeModels(oneModel(vegetation::TreeForm::Conifer));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("--tree-budget-mb"), std::string::npos) << s.error().message;
}

}  // namespace
}  // namespace vegstream::render::testing
