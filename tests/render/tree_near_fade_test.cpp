// The trees' near fade (render/tree_layout.h TreeLodDistances::nearFadeM, shaders/common/
// tree_layout.glsl treeNearKeep, tree.vert's cores): a camera inside a lone conifer's crown (15 m
// tall, 5 m wide, the camera 8 m up beside its trunk) at 160 × 90, MSAA 4, on lavapipe with
// validation on. With the fade off the crown's cards fill the view, some of them nearer than a
// metre; with 4 m no tree surface is drawn nearer than half of it (the depth read back, turned
// into distances: cards, trunk and core alike) and the view opens. From afar, where nothing lies
// within the fade (20 m away), the frames with and without it are the same byte for byte.
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "gpu_test_fixture.h"
#include "render/png_writer.h"
#include "lone_tree.h"

namespace vegstream::render::testing {
namespace {

constexpr float kTreeHeight = 15.0f, kCrown = 5.0f;
constexpr uint32_t kW = 160, kH = 90;

struct Seen {
  size_t treePixels = 0;  // differ from the bare frame by more than 12 in a channel
  size_t nearPixels = 0;  // of those, nearer the camera than `nearM` (the read-back depth)
  double nearestM = 1e9;  // the nearest tree pixel's distance
};

Seen look(const FrameResult& bare, const FrameResult& f, const Camera& cam, double nearM) {
  Seen s;
  const glm::dmat4 inv = glm::inverse(projection(cam, double(kW) / kH) * viewRotation(cam));
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const size_t i = size_t{y} * kW + x;
      bool tree = false;
      for (int c = 0; c < 3; ++c)
        tree |= std::abs(int(f.color->rgba[i * 4 + c]) - int(bare.color->rgba[i * 4 + c])) > 12;
      if (!tree) continue;
      ++s.treePixels;
      const float depth = f.depth->depth[i];
      if (depth <= 0.0f) continue;
      const glm::dvec4 p = inv * glm::dvec4((x + 0.5) / (kW / 2.0) - 1.0, (y + 0.5) / (kH / 2.0) - 1.0, depth, 1.0);
      const double d = glm::length(glm::dvec3(p) / p.w);
      s.nearestM = std::min(s.nearestM, d);
      if (d < nearM) ++s.nearPixels;
    }
  return s;
}

void dump(const FrameResult& f, const std::string& name) {  // VEGSTREAM_TREE_TEST_PNG=DIR: for a person to look
  const char* dir = std::getenv("VEGSTREAM_TREE_TEST_PNG");
  if (dir && f.color) (void)writePng(std::string(dir) + "/" + name + ".png", *f.color);
}

constexpr uint32_t kSeed = 0x2545f491u;

class TreeNearFadeTest : public GpuTest {
 protected:
  // A renderer of kW × kH, MSAA 4, the lone conifer its one model.
  std::unique_ptr<Renderer> coniferRenderer() {
    auto r = makeRenderer(kW, kH, 4);
    if (!r) return nullptr;
    EXPECT_TRUE(r->setImageryLayers(1).ok());
    const std::vector<TreeModelSet> sets = {loneConifer(kTreeHeight, kCrown)};
    EXPECT_TRUE(r->setTreeModels(sets).ok());
    return r;
  }
  const glm::dvec3 sun_ = glm::normalize(glm::dvec3(-0.5, -0.6, 0.62));
};

TEST_F(TreeNearFadeTest, ACameraInsideACrownSeesPastTheBranchesAtItsLens) {
  auto r = coniferRenderer();
  ASSERT_TRUE(r);
  LoneTree scene(kTreeHeight, kCrown, kSeed);
  Camera cam;
  cam.position = {0.7, -0.4, 8.0};
  cam.forward = glm::normalize(glm::dvec3(0.15, 1.0, -0.05));
  cam.verticalFovDeg = 60.0;
  cam.nearM = 0.1;
  const FrameResult bare = scene.render(*r, cam, sun_, false, false, true, 0.0f);
  const FrameResult off = scene.render(*r, cam, sun_, true, false, false, 0.0f);
  const FrameResult on = scene.render(*r, cam, sun_, true, false, false, 4.0f);
  ASSERT_TRUE(bare.color && off.color && on.color && off.depth && on.depth);
  dump(off, "near_fade_off");
  dump(on, "near_fade_4m");
  const Seen seenOff = look(bare, off, cam, 1.6), seenOn = look(bare, on, cam, 1.6);
  std::printf("near fade off: %zu tree pixels, %zu nearer than 1.6 m (nearest %.2f m)\n", seenOff.treePixels,
              seenOff.nearPixels, seenOff.nearestM);
  std::printf("near fade 4 m: %zu tree pixels, %zu nearer than 1.6 m (nearest %.2f m)\n", seenOn.treePixels,
              seenOn.nearPixels, seenOn.nearestM);
  // Without the fade the camera is among the cards: they fill most of the view, some within 1.6 m.
  EXPECT_GT(seenOff.treePixels, size_t{kW} * kH / 2);
  EXPECT_GT(seenOff.nearPixels, 0u);
  // With it nothing of the tree is drawn within 1.6 m (the fade's inner half, 2 m, less a margin),
  // and the view opens.
  EXPECT_EQ(seenOn.nearPixels, 0u);
  EXPECT_GE(seenOn.nearestM, 1.6);
  EXPECT_LT(seenOn.treePixels, seenOff.treePixels * 9 / 10);
}

TEST_F(TreeNearFadeTest, NothingChangesWhereNoTreeIsNear) {
  auto r = coniferRenderer();
  ASSERT_TRUE(r);
  LoneTree scene(kTreeHeight, kCrown, kSeed);
  Camera cam;
  cam.position = {0.0, -20.0, 7.0};
  cam.forward = glm::normalize(glm::dvec3(0.0, 20.0, 0.5));
  cam.verticalFovDeg = 50.0;
  cam.nearM = 0.5;
  const FrameResult off = scene.render(*r, cam, sun_, true, false, true, 0.0f);
  const FrameResult on = scene.render(*r, cam, sun_, true, false, false, 4.0f);
  const FrameResult bare = scene.render(*r, cam, sun_, false, false, false, 4.0f);
  ASSERT_TRUE(off.color && on.color && bare.color);
  EXPECT_GT(look(bare, on, cam, 0.0).treePixels, size_t{400});  // the tree is in view
  EXPECT_EQ(off.color->rgba, on.color->rgba);
  EXPECT_EQ(off.depth->depth, on.depth->depth);
}

}  // namespace
}  // namespace vegstream::render::testing
