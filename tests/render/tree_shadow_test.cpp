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
#include "lone_tree.h"
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
  // The crown width is the diameter of the crown's area from above (treeScale in tree_layout.glsl).
  const double sxy = std::clamp(crownM / (2.0 * std::max(model.crownAreaRadiusM, 0.1f)), 0.6 * sz, 3.5 * sz);
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
    auto cross = [](glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
      return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
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

// Connected components (8-neighbours) of the set pixels of `m`, of at least `minPixels` each.
int components(std::vector<uint8_t> m, size_t minPixels) {
  int n = 0;
  std::vector<size_t> stack;
  for (size_t s = 0; s < m.size(); ++s) {
    if (!m[s]) continue;
    size_t size = 0;
    m[s] = 0;
    stack.push_back(s);
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      ++size;
      const int x = int(i % kW), y = int(i / kW);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, v = y + dy;
          if (u < 0 || v < 0 || u >= int(kW) || v >= int(kH)) continue;
          const size_t j = size_t(v) * kW + size_t(u);
          if (m[j]) m[j] = 0, stack.push_back(j);
        }
    }
    n += size >= minPixels ? 1 : 0;
  }
  return n;
}

// The sun's direction (towards it) from its elevation and azimuth (clockwise from north).
struct SunCase {
  double elevationDeg, azimuthDeg;
  glm::dvec3 towards() const {
    const double el = glm::radians(elevationDeg), az = glm::radians(azimuthDeg);
    return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
  }
};

// The visible ground's pixels (not the tree's: they differ from the bare frame; depth on z = 0),
// where each lies and how much the shadow darkens it (green, of 255).
struct Ground {
  std::vector<uint8_t> visible;
  std::vector<glm::dvec2> at;
  std::vector<double> drop;
  double deepest = 0.0;
};

Ground visibleGround(const FrameResult& bare, const FrameResult& lit, const FrameResult& shaded, const Camera& cam) {
  const glm::dmat4 inv = glm::inverse(projection(cam, double(kW) / kH) * viewRotation(cam));
  Ground g{std::vector<uint8_t>(size_t{kW} * kH, 0), std::vector<glm::dvec2>(size_t{kW} * kH),
           std::vector<double>(size_t{kW} * kH, 0.0)};
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const size_t i = size_t{y} * kW + x;
      bool treePixel = false;
      for (int c = 0; c < 3; ++c)
        treePixel |= std::abs(int(lit.color->rgba[i * 4 + c]) - int(bare.color->rgba[i * 4 + c])) > 12;
      const float depth = shaded.depth->depth[i];
      if (treePixel || depth <= 0.0f) continue;
      const glm::dvec4 p = inv * glm::dvec4((x + 0.5) / (kW / 2.0) - 1.0, (y + 0.5) / (kH / 2.0) - 1.0, depth, 1.0);
      const glm::dvec3 world = glm::dvec3(p) / p.w + cam.position;
      if (std::abs(world.z) > 0.3) continue;
      g.visible[i] = 1;
      g.at[i] = glm::dvec2(world);
      g.drop[i] = double(lit.color->rgba[i * 4 + 1]) - double(shaded.color->rgba[i * 4 + 1]);
      g.deepest = std::max(g.deepest, g.drop[i]);
    }
  return g;
}

struct Figures {
  size_t measured = 0, analytic = 0, both = 0;  // visible ground pixels
  int pieces = 0;
};

// Shadowed: darkened by more than half the deepest darkening (the penumbra's middle, where the
// analytic shadow's hard edge lies). VEGSTREAM_TREE_TEST_PNG=DIR writes the comparison (white
// both, red the analytic shadow only, blue the render's only).
Figures compare(const Ground& g, const std::vector<Hull>& hulls, const glm::dvec3& sun, const std::string& name) {
  Figures f;
  std::vector<uint8_t> dark(g.visible.size(), 0);
  ColorImage cmp{kW, kH, std::vector<uint8_t>(size_t{kW} * kH * 4, 255)};
  for (size_t i = 0; i < g.visible.size(); ++i) {
    const bool expected = g.visible[i] && inAnalyticShadow(hulls, g.at[i], sun);
    dark[i] = g.visible[i] && g.drop[i] > 0.5 * g.deepest ? 1 : 0;
    f.measured += dark[i];
    f.analytic += expected ? 1 : 0;
    f.both += (dark[i] && expected) ? 1 : 0;
    const uint8_t other = g.visible[i] ? 0 : 90;
    cmp.rgba[i * 4 + 0] = expected ? 255 : other;
    cmp.rgba[i * 4 + 1] = expected && dark[i] ? 255 : other;
    cmp.rgba[i * 4 + 2] = dark[i] ? 255 : other;
  }
  // Pieces of at least 1 % of the shadow: smaller ones are the ground under the crown seen through
  // the crown's own gaps, cut off from the rest of the shadow in the view by the crown itself.
  f.pieces = components(dark, std::max<size_t>(4, f.measured / 100));
  if (const char* dir = std::getenv("VEGSTREAM_TREE_TEST_PNG"))
    (void)writePng(std::string(dir) + "/" + name + ".png", cmp);
  return f;
}

class TreeShadowTest : public GpuTest, public ::testing::WithParamInterface<SunCase> {};

TEST_P(TreeShadowTest, ALoneTreeCastsOneShadowOfItsCrownsProjectedArea) {
  RendererOptions o = options(kW, kH, 1);
  o.shadowMapSize = 384;
  auto created = Renderer::create(o);
  ASSERT_TRUE(created.ok()) << (created.ok() ? "" : created.error().message);
  Renderer& r = **created;
  ASSERT_TRUE(r.setImageryLayers(1).ok());
  const std::vector<TreeModelSet> sets = {loneConifer(kTreeHeight, kCrown)};
  ASSERT_TRUE(r.setTreeModels(sets).ok());
  const std::vector<Hull> hulls = slices(sets[0].variants[0], kTreeHeight, kCrown);
  const glm::dvec3 sun = GetParam().towards();
  // Straight down over the shadow's middle from 120 m, a narrow view: nearly orthographic.
  const double length = kTreeHeight / std::tan(glm::radians(GetParam().elevationDeg));
  Camera cam;
  cam.position = glm::dvec3(-glm::normalize(glm::dvec2(sun)) * (0.5 * length), 120.0);
  cam.forward = {0.0, 0.0, -1.0};
  cam.up = {0.0, 1.0, 0.0};
  cam.verticalFovDeg = 16.0;
  LoneTree scene(kTreeHeight, kCrown, 0u);  // no yaw, no lean: the slices stand as the model's
  const FrameResult bare = scene.render(r, cam, sun, false, false, true);
  const FrameResult lit = scene.render(r, cam, sun, true, false, false);
  const FrameResult shaded = scene.render(r, cam, sun, true, true, false);
  ASSERT_TRUE(bare.color && lit.color && shaded.color && shaded.depth);
  const std::string name = "lone-tree-" + std::to_string(int(GetParam().elevationDeg));
  if (const char* dir = std::getenv("VEGSTREAM_TREE_TEST_PNG"))
    (void)writePng(std::string(dir) + "/" + name + ".png", *shaded.color);
  const Ground g = visibleGround(bare, lit, shaded, cam);
  const Figures f = compare(g, hulls, sun, name + "-vs-analytic");
  const double px = 2.0 * 120.0 * std::tan(glm::radians(cam.verticalFovDeg / 2.0)) / kH;  // metres per pixel
  std::printf(
      "sun %.0f° up: darkening up to %.0f of 255; shadow %zu px (%.1f m²), analytic %zu px (%.1f m²), "
      "overlap %zu px; %d connected piece(s)\n",
      GetParam().elevationDeg, g.deepest, f.measured, double(f.measured) * px * px, f.analytic,
      double(f.analytic) * px * px, f.both, f.pieces);
  EXPECT_GT(g.deepest, 30.0) << "the shadow must darken the ground";
  EXPECT_EQ(f.pieces, 1) << "the shadow falls apart";
  EXPECT_NEAR(double(f.measured), double(f.analytic), 0.15 * double(f.analytic));
  EXPECT_GE(double(f.both), 0.8 * double(f.analytic)) << "the shadow lies elsewhere than the analytic one";
}

// 35° from the south-west: the shadow runs north-east, across the map's texel rows and columns
// alike; 50° from the east-south-east, shorter and at another slant.
INSTANTIATE_TEST_SUITE_P(Suns, TreeShadowTest, ::testing::Values(SunCase{35.0, 235.0}, SunCase{50.0, 110.0}));

}  // namespace
}  // namespace vegstream::render::testing
