// A lone tree's sun shadow (issue 39 item 8, render/README.md "Sun shadows"): one conifer on a
// flat plane, the sun 35° up in the south-west, seen straight down from 120 m at 320 × 180 on
// lavapipe, validation on. The ground pixels the shadow darkens (the frame with the trees'
// shadows against the same frame without them; the tree's own pixels left out) must form ONE
// connected region — a thin tree's shadow drawn as dashes falls apart into many — whose area is
// within 15 % of the tree's analytic shadow: the ground points whose ray towards the sun passes
// through the tree's envelope, a solid of revolution whose radius at each height is the model's
// own (its vertices' farthest from the axis in that 0.25 m band; the trunk is its lowest bands),
// counted over the same visible pixels. The shadow map is 384² here, so the cascade's texel
// (0.4 m) is the one the gallery's forest still reads its trees' shadows from at 1280 × 720
// (cascade 1 of a 60° view): trunk and crown tips are a texel or less across in the map.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "gpu_test_fixture.h"
#include "render/png_writer.h"
#include "tests/support/plant_field_scene.h"
#include "vegetation/tree_model.h"

namespace vegstream::render::testing {
namespace {

constexpr float kTreeHeight = 15.0f, kCrown = 5.0f;
constexpr uint32_t kW = 320, kH = 180;
constexpr double kBand = 0.25;  // metres: the envelope's height bands

// The crown's slices: the convex hull (x, y) of the model's vertices in each band of kBand, in
// the instance's scale (sz along z, sxy across, as tree.vert and tree_impostor.vert scale them;
// seed 0: no yaw, no lean). The tree's analytic shadow is the union of the slices projected
// along the sun: the needles' gaps filled, the branch tips' reach kept.
using Hull = std::vector<glm::dvec2>;
std::vector<Hull> slices(const vegetation::TreeModel& model, double heightM, double crownM) {
  const double sz = heightM / model.modelHeightM;
  const double shapeY = std::max(model.crownRadiusM, 0.1f);
  const double sxy = std::clamp(crownM / (2.0 * shapeY), 0.6 * sz, 1.6 * sz);
  std::vector<std::vector<glm::dvec2>> pts(static_cast<size_t>(std::ceil(heightM / kBand)) + 1);
  for (const vegetation::TreeVertex& v : model.lod[0].vertices) {
    if (v.kind == 2) continue;  // the core lies inside the cards
    const auto b = static_cast<size_t>(std::clamp(v.position[2] * sz / kBand, 0.0, double(pts.size() - 1)));
    pts[b].push_back(glm::dvec2(v.position[0], v.position[1]) * sxy);
  }
  std::vector<Hull> hulls;
  for (auto& p : pts) {  // Andrew's monotone chain, counter-clockwise
    if (p.size() < 3) {
      hulls.emplace_back();
      continue;
    }
    std::sort(p.begin(), p.end(), [](auto a, auto b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    Hull h(2 * p.size() + 1);
    size_t k = 0;
    auto cross = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
    for (size_t i = 0; i < p.size(); ++i) {
      while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
      h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
      while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
      h[k++] = p[i];
    }
    h.resize(k > 1 ? k - 1 : 0);
    hulls.push_back(std::move(h));
  }
  return hulls;
}

bool insideHull(const Hull& h, glm::dvec2 q) {
  if (h.size() < 3) return false;
  for (size_t i = 0; i < h.size(); ++i) {
    const glm::dvec2 a = h[i], b = h[(i + 1) % h.size()];
    if ((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x) < 0.0) return false;
  }
  return true;
}

// Does the ray from ground point `p` (z = 0) towards the sun pass through a slice of the tree
// standing at the origin?
bool inAnalyticShadow(const std::vector<Hull>& hulls, const glm::dvec2& p, const glm::dvec3& sun) {
  for (size_t b = 0; b < hulls.size(); ++b)
    if (insideHull(hulls[b], p + glm::dvec2(sun) * ((double(b) + 0.5) * kBand / sun.z))) return true;
  return false;
}

// Connected components (8-neighbours) of the set pixels of `m`.
int components(std::vector<uint8_t> m) {
  int n = 0;
  std::vector<size_t> stack;
  for (size_t s = 0; s < m.size(); ++s) {
    if (!m[s]) continue;
    ++n;
    m[s] = 0;
    stack.push_back(s);
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      const int x = int(i % kW), y = int(i / kW);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= int(kW) || v >= int(kH)) continue;
          const size_t j = size_t(v) * kW + size_t(u);
          if (m[j]) m[j] = 0, stack.push_back(j);
        }
    }
  }
  return n;
}

class TreeShadowTest : public GpuTest {};

TEST_F(TreeShadowTest, ALoneTreeCastsOneShadowOfItsCrownsProjectedArea) {
  RendererOptions o = options(kW, kH, 1);
  o.shadowMapSize = 384;
  auto created = Renderer::create(o);
  ASSERT_TRUE(created.ok()) << (created.ok() ? "" : created.error().message);
  Renderer& r = **created;
  ASSERT_TRUE(r.setImageryLayers(1).ok());
  TreeModelSet set;
  set.species = 0;
  for (const vegetation::Species& s : vegetation::defaultSpeciesCatalog().species)
    if (vegetation::isTree(s) && s.tree.form == vegetation::TreeForm::Conifer) {
      set.params = s.tree;
      break;
    }
  ASSERT_EQ(set.params.form, vegetation::TreeForm::Conifer);
  set.variants.push_back(vegetation::buildTreeModel(set.params, kTreeHeight, kCrown, 7u));
  const std::vector<Hull> env = slices(set.variants[0], kTreeHeight, kCrown);
  const std::vector<TreeModelSet> sets = {set};
  ASSERT_TRUE(r.setTreeModels(sets).ok());

  const std::vector<uint8_t> tile = flatTile(150, 140, 120);
  terrain::TerrainMesh plane = flatPlane(kField, 8, 0.0f);
  for (auto& v : plane.vertices) v.uv = fieldUv(v.position.x, v.position.y);
  TerrainDraw draw{&plane};
  draw.imageryLayer = 0;
  const ImageryUpload upload{0, tile.data()};
  // Towards the sun: 35° up, from the south-west (azimuth 235°): the shadow runs north-east,
  // across the map's texel rows and columns alike.
  const double el = glm::radians(35.0), az = glm::radians(235.0);
  const glm::dvec3 sun(std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el));
  TreeInstanceGpu tree{};
  tree.heightM = kTreeHeight;
  tree.crownM = kCrown;
  tree.seed = 0u;  // no yaw, no lean: the slices stand as the model's
  tree.colour = 0xff000000u;
  const std::vector<TreeInstanceGpu> trees = {tree};
  // Straight down over the shadow's middle, a narrow view: nearly orthographic.
  const glm::dvec3 camera = glm::dvec3(-glm::normalize(glm::dvec2(sun)) * 11.0, 120.0);
  Camera cam;
  cam.position = camera;
  cam.forward = {0.0, 0.0, -1.0};
  cam.up = {0.0, 1.0, 0.0};
  cam.verticalFovDeg = 16.0;
  cam.nearM = 1.0;
  auto render = [&](bool withTrees, bool shadows, bool upload0) {
    FrameRequest req;
    req.lighting.exposureEv = 13.0f;  // fixed: frames are compared pixel by pixel
    req.camera = cam;
    req.cameraHeightMsl = camera.z;
    req.lighting.sunDirection = sun;
    req.readbackColor = req.readbackDepth = true;
    req.terrain = {&draw, 1};
    if (upload0) req.imageryUploads = {&upload, 1};
    const std::vector<TreePageUpload> uploads = {{0, 1, trees.data()}};
    const std::vector<uint32_t> counts = {1};
    TreeRequest t;
    t.uploads = uploads;
    t.pageCounts = counts;
    t.shadows = shadows;
    t.lod.fullHeights = t.lod.reducedHeights = 1e6f;  // the full model
    t.cameraEnu[0] = camera.x, t.cameraEnu[1] = camera.y, t.cameraEnu[2] = camera.z;
    if (withTrees) req.trees = &t;
    auto f = r.renderFrame(req);
    EXPECT_TRUE(f.ok());
    return f.ok() ? std::move(*f) : FrameResult{};
  };
  const FrameResult bare = render(false, false, true);
  const FrameResult lit = render(true, false, false);
  const FrameResult shaded = render(true, true, false);
  ASSERT_TRUE(bare.color && lit.color && shaded.color && shaded.depth);
  if (const char* dir = std::getenv("VEGSTREAM_TREE_TEST_PNG")) {
    (void)writePng(std::string(dir) + "/lone-tree-shadow-off.png", *lit.color);
    (void)writePng(std::string(dir) + "/lone-tree-shadow-on.png", *shaded.color);
  }

  // The visible ground: not the tree's pixels (they differ from the bare frame), depth on z = 0.
  const glm::dmat4 inv = glm::inverse(projection(cam, double(kW) / kH) * viewRotation(cam));
  std::vector<uint8_t> ground(size_t{kW} * kH, 0);
  std::vector<glm::dvec2> at(ground.size());
  std::vector<double> drop(ground.size(), 0.0);
  double deepest = 0.0;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const size_t i = size_t{y} * kW + x;
      bool treePixel = false;
      for (int c = 0; c < 3; ++c)
        treePixel |= std::abs(int(lit.color->rgba[i * 4 + c]) - int(bare.color->rgba[i * 4 + c])) > 12;
      const float depth = shaded.depth->depth[i];
      if (treePixel || depth <= 0.0f) continue;
      const glm::dvec4 p = inv * glm::dvec4((x + 0.5) / (kW / 2.0) - 1.0, (y + 0.5) / (kH / 2.0) - 1.0, depth, 1.0);
      const glm::dvec3 world = glm::dvec3(p) / p.w + camera;
      if (std::abs(world.z) > 0.3) continue;
      ground[i] = 1;
      at[i] = glm::dvec2(world);
      drop[i] = double(lit.color->rgba[i * 4 + 1]) - double(shaded.color->rgba[i * 4 + 1]);
      deepest = std::max(deepest, drop[i]);
    }
  // Shadowed: darkened by more than half the deepest darkening (the penumbra's middle, where the
  // analytic shadow's hard edge lies).
  std::vector<uint8_t> dark(ground.size(), 0);
  size_t measured = 0, analytic = 0, both = 0, groundPixels = 0;
  for (size_t i = 0; i < ground.size(); ++i) {
    if (!ground[i]) continue;
    ++groundPixels;
    dark[i] = drop[i] > 0.5 * deepest ? 1 : 0;
    const bool expected = inAnalyticShadow(env, at[i], sun);
    measured += dark[i];
    analytic += expected ? 1 : 0;
    both += (dark[i] && expected) ? 1 : 0;
  }
  if (const char* dir = std::getenv("VEGSTREAM_TREE_TEST_PNG")) {  // white both, red analytic only, blue render only
    ColorImage cmp{kW, kH, std::vector<uint8_t>(size_t{kW} * kH * 4, 255)};
    for (size_t i = 0; i < ground.size(); ++i) {
      const bool a = ground[i] && inAnalyticShadow(env, at[i], sun), d = dark[i] != 0;
      const uint8_t v = ground[i] ? 0 : 90;
      cmp.rgba[i * 4 + 0] = a ? 255 : v;
      cmp.rgba[i * 4 + 1] = a && d ? 255 : v;
      cmp.rgba[i * 4 + 2] = d ? 255 : v;
    }
    (void)writePng(std::string(dir) + "/lone-tree-shadow-vs-analytic.png", cmp);
  }
  const double px = 2.0 * 120.0 * std::tan(glm::radians(cam.verticalFovDeg / 2.0)) / kH;  // metres per pixel
  const int pieces = components(dark);
  std::printf("deepest darkening %.0f of 255; shadow %zu px (%.1f m²), analytic %zu px (%.1f m²), overlap %zu px; "
              "%d connected piece(s); %zu visible ground px\n",
              deepest, measured, double(measured) * px * px, analytic, double(analytic) * px * px, both, pieces, groundPixels);
  EXPECT_GT(deepest, 30.0) << "the shadow must darken the ground";
  EXPECT_EQ(pieces, 1) << "the shadow falls apart";
  EXPECT_NEAR(double(measured), double(analytic), 0.15 * double(analytic));
  EXPECT_GE(double(both), 0.8 * double(analytic)) << "the shadow lies elsewhere than the analytic one";
}

}  // namespace
}  // namespace vegstream::render::testing
