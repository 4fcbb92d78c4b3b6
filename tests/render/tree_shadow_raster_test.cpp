// The trees' shadow rasteriser in compute (shaders/tree_shadow_raster.comp) keeps each texel's
// nearest depth to the sun through an atomic max, so the sun shadow map must not depend on which
// workgroup takes which caster or which 8 × 8 block of it, nor on the order the casters come in.
// A forest of two models (a conifer and a broadleaf, their casters in one sequence) on a flat
// plane, crowns overlapping along the sun, is drawn by fresh renderers whose rasteriser shares
// the work out differently (RendererOptions::treeShadowGroups and treeShadowLayers): 4096 groups
// in 1 or 16 layers (a GPU's), 64 in 5 (60 groups) and 16 in 16, against the device's default:
// every cascade's map must be the same bit for bit, and so must the frames. Lavapipe, 160 × 90,
// validation on.
#include <array>
#include <cstdio>
#include <vector>

#include "gpu_test_fixture.h"
#include "render/shadow_cascades.h"
#include "lone_tree.h"

namespace vegstream::render::testing {
namespace {

constexpr uint32_t kW = 160, kH = 90, kMap = 512;
constexpr size_t kLayerTexels = size_t{kMap} * kMap;

// 160 trees of 10–20 m over 80 × 150 m ahead of the camera, the two models mixed, each with its
// own seed (yaw, lean): a deterministic scatter, dense enough that crowns shadow each other.
std::vector<TreeInstanceGpu> forest() {
  std::vector<TreeInstanceGpu> trees;
  uint32_t state = 0x2545f491u;
  auto next = [&]() {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  for (uint32_t i = 0; i < 160; ++i) {
    TreeInstanceGpu t{};
    t.position[0] = -40.0f + 80.0f * next();
    t.position[1] = -10.0f + 150.0f * next();
    t.model = i % 2;
    t.heightM = 10.0f + 10.0f * next();
    t.crownM = 0.35f * t.heightM;
    t.seed = 0x9e3779b9u * (i + 1);
    t.colour = 0xff000000u;  // no imagery under it: the species' own leaves
    trees.push_back(t);
  }
  return trees;
}

struct Drawn {
  std::vector<uint32_t> map;
  ColorImage color;
};

class TreeShadowRasterTest : public GpuTest {
 protected:
  // One frame of the forest with the sun's shadows, by a fresh renderer (every cascade drawn on
  // its first frame) whose rasteriser uses `groups` in `layers` (0: the device's, as the cascades ask).
  Drawn draw(uint32_t groups, uint32_t layers) {
    RendererOptions o = options(kW, kH, 1);
    o.shadowMapSize = kMap;
    o.treeShadowGroups = groups;
    o.treeShadowLayers = layers;
    auto created = Renderer::create(o);
    EXPECT_TRUE(created.ok()) << (created.ok() ? "" : created.error().message);
    if (!created.ok()) return {};
    Renderer& r = **created;
    EXPECT_TRUE(r.setImageryLayers(1).ok());
    const std::vector<TreeModelSet> sets = {firstTreeOfForm(vegetation::TreeForm::Conifer, 15.0f, 5.0f),
                                            firstTreeOfForm(vegetation::TreeForm::Broadleaf, 15.0f, 7.0f)};
    EXPECT_TRUE(r.setTreeModels(sets).ok());
    LoneTree scene(15.0f, 5.0f, 0u);  // its plane, with the forest in place of its one tree
    scene.trees = forest();
    Camera cam;
    cam.position = {0.0, -40.0, 30.0};
    cam.forward = glm::normalize(glm::dvec3(0.0, 60.0, -30.0));
    cam.verticalFovDeg = 50.0;
    const glm::dvec3 sun = glm::normalize(glm::dvec3(-0.6, -0.5, 0.45));  // low, from the south-west
    FrameResult f = scene.render(r, cam, sun, true, true, true);
    EXPECT_TRUE(f.color);
    auto map = r.readSunShadowMap();
    EXPECT_TRUE(map.ok()) << (map.ok() ? "" : map.error().message);
    if (!map.ok() || !f.color) return {};
    return {std::move(*map), *f.color};
  }
};

TEST_F(TreeShadowRasterTest, TheMapIsTheSameHoweverTheWorkIsSharedOut) {
  const Drawn base = draw(0, 0);
  ASSERT_EQ(base.map.size(), kLayerTexels * kShadowCascades);
  // The forest casts into every cascade, and its crowns cover each other there.
  std::array<size_t, kShadowCascades> covered{};
  for (size_t c = 0; c < size_t(kShadowCascades); ++c)
    for (size_t i = 0; i < kLayerTexels; ++i) covered[c] += base.map[c * kLayerTexels + i] != 0u ? 1u : 0u;
  std::printf("covered texels per cascade: %zu %zu %zu of %zu\n", covered[0], covered[1], covered[2], kLayerTexels);
  for (size_t c = 0; c < size_t(kShadowCascades); ++c) EXPECT_GT(covered[c], 500u) << "cascade " << c;
  const std::array<std::array<uint32_t, 2>, 4> shares = {{{4096, 1}, {4096, 16}, {64, 5}, {16, 16}}};
  for (const auto& [groups, layers] : shares) {
    const Drawn other = draw(groups, layers);
    ASSERT_EQ(other.map.size(), base.map.size()) << groups << " groups in " << layers << " layers";
    std::array<size_t, kShadowCascades> differ{};
    for (size_t i = 0; i < base.map.size(); ++i) differ[i / kLayerTexels] += base.map[i] != other.map[i] ? 1u : 0u;
    for (size_t c = 0; c < size_t(kShadowCascades); ++c)
      EXPECT_EQ(differ[c], 0u) << "cascade " << c << ": texels that differ with " << groups << " groups in " << layers
                               << " layers";
    EXPECT_EQ(pixelsOffBy(base.color, other.color, 0), 0u) << groups << " groups in " << layers << " layers";
  }
}

}  // namespace
}  // namespace vegstream::render::testing
