// Procedural tree models (issue 20). The vertex layout — each vertex's branch index and axial
// coordinate x, the branch table of frames, lengths, beam fits and resonances — is seed
// ../shared/seeds/002_e402409f584e6b0c.txt §4.3 (notes 002 §1.3, Table 4.2). The branching itself
// is this project's own procedural recipe, in the spirit of Weber and Penn (SIGGRAPH 1995): a crown
// envelope (a cone for conifers, an ellipsoid for broadleaves) filled by straight branches and
// large cards, jittered per branch by Philox keyed by the variant seed (the crowns themselves:
// tree_crowns.cpp). Branch axes are straight, so a vertex's `along` is exactly its x on the axis.
//
// Bark: open tubes along the straight axes, rings 0.1 × the height apart (Full: trunk 8–12 rings
// of 8 sides, level 1 3–4 rings of 6 sides, levels 2 and 3 one segment of 4 and 3 sides, whose
// centimetres show no more). Budget: Full stays near 12 000 triangles, and its cards cover the
// crown's side view about 5 (conifer) or 6 (broadleaf) layers deep — each layer costs its pixels,
// hidden or not, and 30–40 layers cost the H200 40 ms a frame in the Kolob forest — spread evenly
// over the last-level branches, on their outer part. Reduced: trunk and level-1 bark of 4 sides,
// and one card 1.8 × as long and wide for every four Full cards of a level-1 branch's subtree,
// centred where the four are and hung on that level-1 branch (its `along` where the twig leaves
// it): the silhouette stays.
#include "vegetation/tree_model.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <mutex>
#include <utility>

#include "vegetation/crown_projection.h"
#include "vegetation/tree_core.h"
#include "vegetation/tree_crowns.h"

namespace vegstream::vegetation {
namespace {

using namespace tree_detail;
constexpr int kMaxTriangles = 12000;
// Card layers over the crown's side view, Full (Reduced: about 0.8 of it): about three opaque
// layers, the needle sprays filling 60 % of their cards, the leaf clumps 50 %.
float cardLayers(TreeForm form) { return form == TreeForm::Conifer ? 4.25f : 5.25f; }
constexpr float kReducedCardScale = 1.8f;
constexpr size_t kReducedSkip = 7;  // Reduced keeps six of every seven groups of Full cards
// A broadleaf's trunk forks this share of the height above the crown's lowest leaves.
constexpr float kForkAboveCrownBase = 0.08f;

struct Rings {
  uint32_t lo, hi, sides;
};

// Rings and sides of a branch's tube by level (lo == 0: not drawn at this level of detail).
Rings ringsFor(TreeLod lod, uint32_t level) {
  if (lod == TreeLod::Full) {
    constexpr Rings kFull[] = {{8, 12, 8}, {3, 4, 6}, {2, 2, 4}, {2, 2, 3}};
    return kFull[std::min(level, 3u)];
  }
  constexpr Rings kReduced[] = {{3, 6, 4}, {2, 3, 4}};
  return level < 2 ? kReduced[level] : Rings{0, 0, 0};
}

uint32_t ringCount(const Rings& rings, float length, float heightM, TreeLod lod) {
  const float spacing = (lod == TreeLod::Full ? 0.1f : 0.2f) * heightM;
  const auto wanted = static_cast<uint32_t>(std::ceil(length / spacing)) + 1u;
  return std::clamp(wanted, rings.lo, rings.hi);
}

// One branch's open tube: rings along the straight axis, radius tapering linearly.
void addTube(TreeMesh& mesh, const Skeleton& k, uint32_t index, const TreeParams& p, float heightM, TreeLod lod) {
  const TreeBranch& b = k.branches[index];
  const Rings rings = ringsFor(lod, b.level);
  if (rings.lo == 0) return;
  const uint32_t count = ringCount(rings, b.length, heightM, lod);
  const vec3 t = load(b.t), r = load(b.r), s = load(b.s);
  const float r0 = k.rootRadius[index];
  const float slope = r0 * (1.0f - p.taper) / b.length;  // the cone's normals lean towards the tip
  const bool pointed = b.level == 0 && p.form == TreeForm::Conifer;
  const auto first = static_cast<uint32_t>(mesh.vertices.size());
  for (uint32_t ring = 0; ring < count; ++ring) {
    const float x = static_cast<float>(ring) / static_cast<float>(count - 1);
    float radius = radiusAt(k, index, x, p.taper);
    if (pointed && ring + 1 == count) radius = 0.02f * r0;  // the leader ends in a point
    for (uint32_t side = 0; side <= rings.sides; ++side) {
      const float u = static_cast<float>(side) / static_cast<float>(rings.sides);
      const vec3 out = r * std::cos(2.0f * kPi * u) + s * std::sin(2.0f * kPi * u);
      TreeVertex v{};
      store(v.position, pointOn(b, x) + out * radius);
      store(v.normal, glm::normalize(out + t * slope));
      v.branch = index;
      v.along = x;
      v.uv[0] = u;
      v.uv[1] = x * b.length / (2.0f * kPi * r0);
      mesh.vertices.push_back(v);
    }
  }
  const uint32_t stride = rings.sides + 1;
  for (uint32_t ring = 0; ring + 1 < count; ++ring) {
    for (uint32_t side = 0; side < rings.sides; ++side) {
      const uint32_t a = first + ring * stride + side, c = a + stride + 1;
      mesh.indices.insert(mesh.indices.end(), {a, a + 1, c, a, c, c - 1});
    }
  }
}

// A conifer's needle spray narrows to 0.6 of its width at the tip (shaders/common/tree_shading.glsl
// treeCardShape: width 1 − 0.4 v), and nothing covers the card outside that: its card is that
// trapezoid rather than the whole quad, with each corner's uv where it lies, so the picture is the
// same and a fifth of the card's fragments — launched, then dropped by their coverage — are never
// made. On the H200 the trees' cards are bound by how many fragments are launched.
constexpr float kConiferTipWidth = 0.6f;

void addCardQuad(TreeMesh& mesh, const Card& c, TreeForm form) {
  const vec3 across = glm::cross(c.axis, c.normal) * (0.5f * c.width);  // (across × axis) ∥ normal: front face
  const vec3 tip = c.stem + c.axis * c.length;
  const float t = form == TreeForm::Conifer ? kConiferTipWidth : 1.0f;  // the tip's share of the width
  const vec3 corners[4] = {c.stem - across, c.stem + across, tip + t * across, tip - t * across};
  const float us[4] = {0.0f, 1.0f, 0.5f + 0.5f * t, 0.5f - 0.5f * t}, vs[4] = {0.0f, 0.0f, 1.0f, 1.0f};
  const auto first = static_cast<uint32_t>(mesh.vertices.size());
  for (int i = 0; i < 4; ++i) {
    TreeVertex v{};
    store(v.position, corners[i]);
    store(v.normal, c.normal);
    v.branch = c.branch;
    v.along = c.along;
    v.uv[0] = us[i], v.uv[1] = vs[i];
    v.kind = 1;
    v.flutter = vs[i];
    mesh.vertices.push_back(v);
  }
  mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

// The level-1 branch a branch belongs to, and where its level-2 ancestor leaves it.
void levelOneAncestor(const Skeleton& k, uint32_t b, uint32_t& ancestor, float& along) {
  along = 0.0f;
  while (k.branches[b].level > 1) {
    along = k.branches[b].parentAlong;
    b = static_cast<uint32_t>(k.branches[b].parent);
  }
  ancestor = b;
  if (k.branches[b].level < 1) along = 0.0f;
}

// One card for every (up to) four Full cards of a level-1 subtree, 1.8 × as long and wide: four
// cards cover less than four times one (they overlap), so 2 × drew a side view 10–21 % larger
// than Full's, 1.8 × draws it within ±8 % (tests/vegetation/tree_model_test.cpp); six groups of
// every seven.
std::vector<Card> reducedCards(const Skeleton& k, const Envelope& env) {
  std::vector<Card> out;
  size_t i = 0, groups = 0;
  while (i < k.cards.size()) {
    uint32_t ancestor = 0;
    float along = 0.0f;
    levelOneAncestor(k, k.cards[i].branch, ancestor, along);
    vec3 centre(0.0f), axis(0.0f), normal(0.0f);
    float length = 0.0f, width = 0.0f;
    size_t n = 0;
    for (; n < 4 && i + n < k.cards.size(); ++n) {
      uint32_t other = 0;
      float unused = 0.0f;
      levelOneAncestor(k, k.cards[i + n].branch, other, unused);
      if (other != ancestor) break;
      const Card& c = k.cards[i + n];
      centre += c.stem + c.axis * (0.5f * c.length);
      axis += c.axis, normal += c.normal;
      length += c.length, width += c.width;
    }
    const float share = 1.0f / static_cast<float>(n);
    Card big = k.cards[i];
    if (glm::length(axis) > 1e-3f) big.axis = glm::normalize(axis);
    normal -= big.axis * glm::dot(normal, big.axis);
    if (glm::length(normal) > 1e-3f)
      big.normal = glm::normalize(normal);
    else
      big.normal = glm::normalize(glm::cross(big.axis, big.axis.z < 0.9f ? vec3(0, 0, 1) : vec3(1, 0, 0)));
    big.length = kReducedCardScale * length * share;
    big.width = kReducedCardScale * width * share;
    big.stem = centre * share - big.axis * (0.5f * big.length);
    big.branch = ancestor;
    big.along = along;
    fitCard(big, env);
    // Every kReducedSkip-th group is left out: the crown's core fills what it showed, and on the
    // H200 each layer of cards costs its pixels (render/README.md "Trees on the H200").
    if (++groups % kReducedSkip != 0) out.push_back(big);
    i += n;
  }
  return out;
}

Skeleton growSkeleton(const TreeParams& p, const Envelope& env, float scale, float trunkRadius, uint32_t seed,
                      const BeamFit& fit) {
  Skeleton k;
  Random rng(seed);
  const float trunkLength = p.form == TreeForm::Conifer ? env.height : env.base + kForkAboveCrownBase * env.height;
  addBranch(k, -1, 0.0f, vec3(0.0f, 0.0f, 1.0f), trunkLength, trunkRadius, fit);
  if (p.form == TreeForm::Conifer)
    growConifer(k, p, env, scale, rng, fit);
  else
    growBroadleaf(k, p, env, scale, rng, fit);
  if (p.branchLevels >= 3) growBranchlets(k, p, env, scale, rng, fit);
  // The card budget: what the Full bark leaves of kMaxTriangles, two triangles a card; and at
  // most kCardLayers layers of cards over the crown's side view, since every layer costs its
  // pixels (alpha-tested cards are not rejected by the depth test before shading).
  uint32_t barkTriangles = 0, lastLevel = 0;
  for (const TreeBranch& b : k.branches) {
    const Rings rings = ringsFor(TreeLod::Full, b.level);
    barkTriangles += 2 * rings.sides * (ringCount(rings, b.length, env.height, TreeLod::Full) - 1);
    lastLevel += b.level == p.branchLevels ? 1u : 0u;
  }
  const auto byTriangles = static_cast<uint32_t>(std::max(800, (kMaxTriangles - static_cast<int>(barkTriangles)) / 2));
  const float size = p.leafSizeM * std::min(scale, 1.0f);
  // A card at a random angle shows half its area from the side.
  const auto byLayers =
      static_cast<uint32_t>(cardLayers(p.form) * sideArea(env) / (0.5f * cardArea(p.form, size)));
  const uint32_t total = std::clamp(std::min(byTriangles, byLayers), 1u, lastLevel * p.leavesPerTwig);
  addCards(k, p, env, total, size, rng);
  return k;
}

// fitTaperedBeamFreeTip is a numerical fit of ~2 ms, the same for every model of a species:
// computed once per taper (a catalog has a handful) and kept.
BeamFit beamFitFor(float taper) {
  static std::mutex mutex;
  static std::vector<std::pair<float, BeamFit>> fits;
  const std::lock_guard<std::mutex> lock(mutex);
  for (const auto& [t, fit] : fits)
    if (t == taper) return fit;
  const BeamFit fit = fitTaperedBeamFreeTip(taper);
  if (fits.size() < 64) fits.emplace_back(taper, fit);
  return fit;
}

float meshRadius(const TreeMesh& mesh) {
  float radius = 0.0f;
  for (const TreeVertex& v : mesh.vertices) radius = std::max(radius, std::hypot(v.position[0], v.position[1]));
  return radius;
}

}  // namespace

TreeModel buildTreeModel(const TreeParams& params, float heightM, float crownWidthM, uint32_t variantSeed) {
  assert(heightM > 0.0f && crownWidthM > 0.0f);
  assert(params.branchLevels >= 2 && params.branchLevels <= kMaxBranchLevels);
  assert(params.branches >= 3 && params.twigs >= 1 && params.leavesPerTwig >= 1);
  assert(params.branchAngleDeg >= 10.0f && params.branchAngleDeg <= 120.0f);
  assert(params.taper >= 0.05f && params.taper <= 1.0f && params.trunkRadiusM > 0.0f && params.leafSizeM > 0.0f);
  Random rng(variantSeed ^ 0x9e3779b9u);
  // Conifers: foliage from 22–32 % of the height; broadleaves: the trunk forks at 30–40 %.
  const float crownBase = params.form == TreeForm::Conifer
                              ? rng.range(0.22f, 0.32f) * heightM
                              : (rng.range(0.3f, 0.4f) - kForkAboveCrownBase) * heightM;
  const Envelope env{params.form, heightM, 0.5f * crownWidthM, crownBase};
  const float trunkRadius = params.trunkRadiusM * heightM / 10.0f;
  // The free-tip fit: within 1 % of the analytic beam for every taper the catalog allows (≤ 0.9).
  const BeamFit fit = beamFitFor(params.taper);

  // Grow, and grow again shorter while the crown is wider than asked (cards and droop can carry
  // it past the envelope): at most a few rounds, each the same deterministic recipe.
  TreeModel model;
  float scale = 1.0f;
  for (int round = 0; round < 6; ++round) {
    const Skeleton k = growSkeleton(params, env, scale, trunkRadius, variantSeed, fit);
    TreeModel candidate;
    candidate.modelHeightM = heightM;
    candidate.branches = k.branches;
    for (TreeLod lod : {TreeLod::Full, TreeLod::Reduced}) {
      TreeMesh& mesh = candidate.lod[static_cast<size_t>(lod)];
      for (uint32_t b = 0; b < k.branches.size(); ++b) addTube(mesh, k, b, params, heightM, lod);
      for (const Card& c : lod == TreeLod::Full ? k.cards : reducedCards(k, env)) addCardQuad(mesh, c, params.form);
    }
    const CrownCore core = crownCoreOf(candidate.lod[0]);
    for (TreeMesh& mesh : candidate.lod) addCrownCore(mesh, core, k.branches[0].length);
    candidate.crownRadiusM = std::max(meshRadius(candidate.lod[0]), meshRadius(candidate.lod[1]));
    model = std::move(candidate);
    if (model.crownRadiusM <= 1.08f * env.radius) break;
    scale *= 1.04f * env.radius / model.crownRadiusM;
  }
  model.crownAreaRadiusM = std::min(crownProjectionRadius(model.lod[0]), model.crownRadiusM);
  return model;
}

}  // namespace vegstream::vegetation
