// Procedural tree models (issue 20). The vertex layout — each vertex's branch index and axial
// coordinate x, the branch table of frames, lengths, beam fits and resonances — is seed
// ../shared/seeds/002_e402409f584e6b0c.txt §4.3 (notes 002 §1.3, Table 4.2). The branching itself
// is this project's own procedural recipe, in the spirit of Weber and Penn (SIGGRAPH 1995): a crown
// envelope (a cone for conifers, an ellipsoid for broadleaves) and straight branches whose lengths
// are a share of the distance to that envelope, jittered per branch by Philox keyed by the
// variant seed. Branch axes are straight, so a vertex's `along` is exactly its x on the axis.
//
// Conifer: one leader from the ground to the top (its last ring closes to a point), whorls of
// level-1 branches from about a quarter of the height up, angled at branchAngleDeg from the axis
// and drooping more the lower they are, reaching 80 % of the way to the cone; level-2 twigs
// alternately left and right in a flat spray; needle cards (0.35 × as wide as long) along the
// last level. Broadleaf: the trunk to 35–45 % of the height, where at most 6 limbs fork upwards
// and out (`branches` beyond 6 are ignored: a broadleaf's crown is its few big limbs); twigs all
// around each limb, reaching most of the way to the crown ellipsoid; square leaf cards clustered
// towards the twig ends.
//
// Bark: open tubes along the straight axes, rings 0.1 × the height apart (Full: trunk 8–12 rings,
// level 1 3–5, levels 2–3 2–3; 8 sides on the trunk and level 1, 6 and 4 on the thin levels 2
// and 3, whose few millimetres show no more). Budget: Full stays near 12 000 triangles — when the
// last level's cards would exceed what the bark leaves of that, fewer cards per branch are made,
// each larger by √(leavesPerTwig / made) so the crown is as dense. Reduced: trunk and level-1
// bark of 4 sides, and one card 1.8 × as long and wide for every four Full cards of a level-1
// branch's subtree, centred where the four are and hung on that level-1 branch (its `along`
// where the twig leaves it): the silhouette stays.
#include "vegetation/tree_model.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "vegetation/philox.h"
#include "vegetation/tree_bending.h"

namespace vegstream::vegetation {
namespace {

using glm::vec3;
constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kGoldenAngle = 2.39996323f;
constexpr int kMaxTriangles = 12000;
constexpr float kReducedCardScale = 1.8f;
constexpr uint32_t kRandomStream = 0x74726565u;  // "tree"

class Random {
 public:
  explicit Random(uint32_t seed) : seed_(seed) {}
  float next() { return u01(philox(counter_++, kRandomStream, seed_).x); }
  float range(float lo, float hi) { return lo + (hi - lo) * next(); }

 private:
  uint32_t seed_;
  uint32_t counter_ = 0;
};

vec3 load(const float (&a)[3]) { return {a[0], a[1], a[2]}; }
void store(float (&a)[3], vec3 v) { a[0] = v.x, a[1] = v.y, a[2] = v.z; }
float horizontal(vec3 p) { return std::sqrt(p.x * p.x + p.y * p.y); }

struct Card {
  vec3 stem, axis, normal;  // stem: the middle of the card's base; axis: unit, stem to tip
  float length, width;
  uint32_t branch;
  float along;
};

struct Skeleton {
  std::vector<TreeBranch> branches;
  std::vector<float> rootRadius;
  std::vector<Card> cards;
};

// The crown's outline: conifers a cone from the crown base to the top (a cylinder below it),
// broadleaves an ellipsoid.
struct Envelope {
  TreeForm form;
  float height, radius, base;

  bool inside(vec3 p) const {
    if (p.z > height || p.z < 0.0f) return false;
    const float rho = horizontal(p);
    if (form == TreeForm::Conifer) return rho <= radius * std::min(1.0f, (height - p.z) / (height - base));
    const float centre = 0.5f * (base + height), half = 0.5f * (height - base);
    const float a = rho / radius, b = (p.z - centre) / half;
    return a * a + b * b <= 1.0f;
  }
  // How far from p along unit d until the envelope is left (0 if p is outside).
  float reach(vec3 p, vec3 d) const {
    if (!inside(p)) return 0.0f;
    const float step = 0.05f * (height + radius);
    float lo = 0.0f, hi = step;
    while (inside(p + d * hi) && hi < 4.0f * (height + radius)) lo = hi, hi += step;
    for (int i = 0; i < 24; ++i) {
      const float mid = 0.5f * (lo + hi);
      (inside(p + d * mid) ? lo : hi) = mid;
    }
    return lo;
  }
};

float radiusAt(const Skeleton& k, uint32_t b, float x, float taper) {
  return k.rootRadius[b] * (1.0f + (taper - 1.0f) * x);
}

vec3 pointOn(const TreeBranch& b, float x) { return load(b.origin) + load(b.t) * (x * b.length); }

uint32_t addBranch(Skeleton& k, int32_t parent, float parentAlong, vec3 direction, float length, float rootRadius,
                   const BeamFit& fit) {
  assert(length > 0.0f && rootRadius > 0.0f);
  TreeBranch b{};
  const vec3 t = glm::normalize(direction);
  // r horizontal (ẑ × t); for an upright branch x̂ made ⟂ t.
  vec3 r = glm::cross(vec3(0.0f, 0.0f, 1.0f), t);
  if (glm::length(r) < 1e-3f) r = vec3(1.0f, 0.0f, 0.0f) - t * t.x;
  r = glm::normalize(r);
  const vec3 s = glm::cross(t, r);
  b.parent = parent;
  b.parentAlong = parentAlong;
  b.level = parent < 0 ? 0u : k.branches[static_cast<size_t>(parent)].level + 1;
  store(b.origin, parent < 0 ? vec3(0.0f) : pointOn(k.branches[static_cast<size_t>(parent)], parentAlong));
  store(b.t, t), store(b.r, r), store(b.s, s);
  b.length = length;
  b.c2 = fit.c2, b.c4 = fit.c4;
  // Eq. 4.20 is Habel's broadleaf law; the seed notes conifer branches behave differently but
  // gives no law for them, so conifers use it too.
  b.frequencyHz = 2.55f * std::pow(length, -0.59f);
  // Tip deflection per unit load (10 m/s): more for thinner, longer branches and higher levels;
  // the trunk's top moves at most 2 % of the height at 10 m/s.
  constexpr float kBase[] = {0.015f, 0.06f, 0.12f, 0.2f};
  const float slenderness = std::clamp(length / rootRadius / 40.0f, 0.5f, 1.5f);
  b.compliance = kBase[std::min(b.level, 3u)] * slenderness;
  if (b.level == 0) b.compliance = std::min(b.compliance, 0.02f);
  k.branches.push_back(b);
  k.rootRadius.push_back(rootRadius);
  return static_cast<uint32_t>(k.branches.size() - 1);
}

// Turns unit `axis` by `angle` towards unit `towards` (⟂ axis).
vec3 tilt(vec3 axis, vec3 towards, float angle) { return axis * std::cos(angle) + towards * std::sin(angle); }

// A child's root radius: thinner than its parent there, and at least 15:1 long (seed §4.4.1).
float childRadius(const Skeleton& k, uint32_t parent, float x, float length, float taper) {
  return std::max(0.002f, std::min(0.6f * radiusAt(k, parent, x, taper), length / 35.0f));
}

// Conifer level-1 whorls from the crown base to near the top; level-2 twigs alternately left and
// right in the branch's horizontal plane.
void growConifer(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng, const BeamFit& fit) {
  const float H = env.height;
  const uint32_t perWhorl = p.branches >= 12 ? 4u : 3u;
  const uint32_t whorls = (p.branches + perWhorl - 1) / perWhorl;
  const float angle = p.branchAngleDeg * kPi / 180.0f;
  for (uint32_t i = 0; i < p.branches; ++i) {
    const uint32_t w = i / perWhorl;
    const float h = static_cast<float>(w) / static_cast<float>(whorls);  // 0 at the crown base
    const float z = env.base + (0.96f * H - env.base) * h +
                    rng.range(-0.3f, 0.3f) * (0.9f * H - env.base) / static_cast<float>(whorls);
    const float azimuth = kGoldenAngle * static_cast<float>(w) +
                          2.0f * kPi * static_cast<float>(i % perWhorl) / static_cast<float>(perWhorl) +
                          rng.range(-0.3f, 0.3f);
    const float droop = (0.3f * (1.0f - h) + rng.range(-0.08f, 0.08f));
    const float theta = std::min(angle + droop, 2.1f);
    const vec3 out(std::cos(azimuth), std::sin(azimuth), 0.0f);
    const vec3 d = tilt(vec3(0.0f, 0.0f, 1.0f), out, theta);
    const float x = z / H;
    const float length = std::max(0.05f, 0.8f * scale * env.reach(vec3(0.0f, 0.0f, z), d) * rng.range(0.9f, 1.05f));
    const uint32_t b = addBranch(k, 0, x, d, length, childRadius(k, 0, x, length, p.taper), fit);
    for (uint32_t j = 0; j < p.twigs; ++j) {
      const TreeBranch& parent = k.branches[b];
      const float along = 0.2f + 0.75f * (static_cast<float>(j) + rng.range(0.2f, 0.8f)) / static_cast<float>(p.twigs);
      const float side = (j % 2 == 0) ? 1.0f : -1.0f;
      const vec3 twigDir = tilt(load(parent.t), load(parent.r) * side, rng.range(0.6f, 0.9f)) - vec3(0.0f, 0.0f, 0.1f);
      const float twigLength = std::max(0.05f, 0.35f * parent.length * (1.0f - 0.5f * along) * rng.range(0.85f, 1.15f));
      addBranch(k, static_cast<int32_t>(b), along, twigDir, twigLength, childRadius(k, b, along, twigLength, p.taper),
                fit);
    }
  }
}

// Broadleaf limbs from the trunk's top, twigs all around each limb.
void growBroadleaf(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng,
                   const BeamFit& fit) {
  const uint32_t limbs = std::min(p.branches, 6u);
  const float angle = p.branchAngleDeg * kPi / 180.0f;
  const float turn = rng.range(0.0f, 2.0f * kPi);
  for (uint32_t i = 0; i < limbs; ++i) {
    const float azimuth =
        turn + 2.0f * kPi * static_cast<float>(i) / static_cast<float>(limbs) + rng.range(-0.35f, 0.35f);
    const vec3 out(std::cos(azimuth), std::sin(azimuth), 0.0f);
    const vec3 d = tilt(vec3(0.0f, 0.0f, 1.0f), out, angle + rng.range(-0.14f, 0.14f));
    const float x = rng.range(0.85f, 1.0f);
    const vec3 origin = pointOn(k.branches[0], x);
    const float length = std::max(0.1f, 0.6f * scale * env.reach(origin, d) * rng.range(0.9f, 1.05f));
    const uint32_t b = addBranch(k, 0, x, d, length, childRadius(k, 0, x, length, p.taper), fit);
    for (uint32_t j = 0; j < p.twigs; ++j) {
      const TreeBranch& limb = k.branches[b];
      const float along = 0.3f + 0.7f * (static_cast<float>(j) + rng.range(0.2f, 0.8f)) / static_cast<float>(p.twigs);
      const float around = kGoldenAngle * static_cast<float>(j) + rng.range(-0.4f, 0.4f);
      vec3 sideways = load(limb.r) * std::cos(around) + load(limb.s) * std::sin(around);
      if (sideways.z < -0.3f) sideways.z = -sideways.z;  // twigs up and out, not into the trunk's shade
      const vec3 twigDir = glm::normalize(tilt(load(limb.t), glm::normalize(sideways), rng.range(0.6f, 1.0f)));
      const vec3 twigOrigin = pointOn(limb, along);
      const float twigLength = std::clamp(0.8f * scale * env.reach(twigOrigin, twigDir), 0.1f, 0.8f * limb.length);
      addBranch(k, static_cast<int32_t>(b), along, twigDir, twigLength, childRadius(k, b, along, twigLength, p.taper),
                fit);
    }
  }
}

// Level-3 branchlets on every level-2 branch (branchLevels == 3).
void growBranchlets(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng,
                    const BeamFit& fit) {
  const uint32_t perTwig = std::max(2u, p.twigs / 2);
  const size_t twigs = k.branches.size();
  for (size_t i = 0; i < twigs; ++i) {
    if (k.branches[i].level != 2) continue;
    for (uint32_t j = 0; j < perTwig; ++j) {
      const TreeBranch& twig = k.branches[i];
      const float along = 0.3f + 0.65f * (static_cast<float>(j) + rng.range(0.2f, 0.8f)) / static_cast<float>(perTwig);
      const float side = (j % 2 == 0) ? 1.0f : -1.0f;
      const vec3 dir = glm::normalize(tilt(load(twig.t), load(twig.r) * side, rng.range(0.5f, 0.8f)));
      const vec3 origin = pointOn(twig, along);
      const float reach = std::max(env.reach(origin, dir), 0.05f);
      const float length = std::clamp(std::min(0.45f * twig.length, 0.8f * scale * reach), 0.04f, twig.length);
      addBranch(k, static_cast<int32_t>(i), along, dir, length,
                childRadius(k, static_cast<uint32_t>(i), along, length, p.taper), fit);
    }
  }
}

// Keeps a card under the top and inside the crown's width (5 % slack): first turns a card that
// pokes over the top downwards, then shortens it.
void fitCard(Card& c, const Envelope& env) {
  for (int i = 0; i < 6; ++i) {
    const vec3 across = glm::cross(c.axis, c.normal) * (0.5f * c.width);
    const vec3 tip = c.stem + c.axis * c.length;
    bool fits = true;
    for (vec3 q : {c.stem - across, c.stem + across, tip - across, tip + across})
      fits = fits && q.z <= env.height && horizontal(q) <= 1.05f * env.radius;
    if (fits) return;
    if (i == 0 && tip.z > env.height && c.axis.z > 0.0f) {
      c.axis.z = -c.axis.z;
      const vec3 normal = c.normal - c.axis * glm::dot(c.normal, c.axis);
      if (glm::length(normal) > 1e-3f)
        c.normal = glm::normalize(normal);
      else
        c.axis.z = -c.axis.z;  // keep the old, consistent frame
    } else {
      c.length *= 0.75f;
    }
  }
}

// The Full cards on every last-level branch.
void addCards(Skeleton& k, const TreeParams& p, const Envelope& env, uint32_t perBranch, float size, Random& rng) {
  const bool conifer = p.form == TreeForm::Conifer;
  const size_t count = k.branches.size();
  for (size_t i = 0; i < count; ++i) {
    const TreeBranch& b = k.branches[i];
    if (b.level != p.branchLevels) continue;
    for (uint32_t j = 0; j < perBranch; ++j) {
      const float share = (static_cast<float>(j) + rng.range(0.2f, 0.8f)) / static_cast<float>(perBranch);
      const float along = conifer ? 0.1f + 0.9f * share : 0.4f + 0.6f * share;
      Card c{};
      c.stem = pointOn(b, along);
      const float side = (j % 2 == 0) ? 1.0f : -1.0f;
      const vec3 jitter(rng.range(-1.0f, 1.0f), rng.range(-1.0f, 1.0f), rng.range(-1.0f, 1.0f));
      c.axis = conifer ? tilt(load(b.t), load(b.r) * side, rng.range(0.4f, 0.8f)) +
                             vec3(0.0f, 0.0f, rng.range(-0.6f, 0.3f)) + 0.15f * jitter
                       : load(b.t) + 0.7f * jitter + vec3(0.0f, 0.0f, 0.3f);
      c.axis = glm::normalize(c.axis);
      // Facing out from the trunk and up, jittered, in the plane ⟂ the card's axis (needle sprays
      // lie flatter than broad leaves, but facing straight up they would vanish from the side).
      const vec3 out =
          horizontal(c.stem) > 1e-3f ? glm::normalize(vec3(c.stem.x, c.stem.y, 0.0f)) : vec3(1.0f, 0.0f, 0.0f);
      vec3 facing = vec3(0.0f, 0.0f, 1.0f) + out * (conifer ? 1.0f : 0.6f) +
                    vec3(rng.range(-0.5f, 0.5f), rng.range(-0.5f, 0.5f), rng.range(-0.3f, 0.3f));
      facing -= c.axis * glm::dot(facing, c.axis);
      c.normal = glm::length(facing) > 1e-3f ? glm::normalize(facing) : glm::normalize(glm::cross(c.axis, load(b.r)));
      if (conifer) {
        // Needle cards along a twig that points out face straight up; rolled about their axis by
        // up to ±65° they make a bottle brush that also shows from the side.
        const float roll = rng.range(-1.13f, 1.13f);
        c.normal = c.normal * std::cos(roll) + glm::cross(c.axis, c.normal) * std::sin(roll);
      }
      c.length = size * rng.range(0.85f, 1.15f);
      c.width = conifer ? 0.35f * c.length : c.length * rng.range(0.8f, 1.0f);
      c.branch = static_cast<uint32_t>(i);
      c.along = along;
      fitCard(c, env);
      k.cards.push_back(c);
    }
  }
}

struct Rings {
  uint32_t lo, hi, sides;
};

// Rings and sides of a branch's tube by level (lo == 0: not drawn at this level of detail).
Rings ringsFor(TreeLod lod, uint32_t level) {
  if (lod == TreeLod::Full) {
    constexpr Rings kFull[] = {{8, 12, 8}, {3, 5, 8}, {2, 3, 6}, {2, 2, 4}};
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

void addCardQuad(TreeMesh& mesh, const Card& c) {
  const vec3 across = glm::cross(c.axis, c.normal) * (0.5f * c.width);  // (across × axis) ∥ normal: front face
  const vec3 tip = c.stem + c.axis * c.length;
  const vec3 corners[4] = {c.stem - across, c.stem + across, tip + across, tip - across};
  const float us[4] = {0.0f, 1.0f, 1.0f, 0.0f}, vs[4] = {0.0f, 0.0f, 1.0f, 1.0f};
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
// than Full's, 1.8 × draws it within ±8 % (tests/vegetation/tree_model_test.cpp).
std::vector<Card> reducedCards(const Skeleton& k, const Envelope& env) {
  std::vector<Card> out;
  size_t i = 0;
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
    out.push_back(big);
    i += n;
  }
  return out;
}

Skeleton growSkeleton(const TreeParams& p, const Envelope& env, float scale, float trunkRadius, uint32_t seed,
                      const BeamFit& fit) {
  Skeleton k;
  Random rng(seed);
  const float trunkLength = p.form == TreeForm::Conifer ? env.height : env.base + 0.12f * env.height;
  addBranch(k, -1, 0.0f, vec3(0.0f, 0.0f, 1.0f), trunkLength, trunkRadius, fit);
  if (p.form == TreeForm::Conifer)
    growConifer(k, p, env, scale, rng, fit);
  else
    growBroadleaf(k, p, env, scale, rng, fit);
  if (p.branchLevels >= 3) growBranchlets(k, p, env, scale, rng, fit);
  // The card budget: what the Full bark leaves of kMaxTriangles, two triangles a card.
  uint32_t barkTriangles = 0, lastLevel = 0;
  for (const TreeBranch& b : k.branches) {
    const Rings rings = ringsFor(TreeLod::Full, b.level);
    barkTriangles += 2 * rings.sides * (ringCount(rings, b.length, env.height, TreeLod::Full) - 1);
    lastLevel += b.level == p.branchLevels ? 1u : 0u;
  }
  const auto budget = static_cast<uint32_t>(std::max(800, (kMaxTriangles - static_cast<int>(barkTriangles)) / 2));
  const uint32_t perBranch = std::clamp(budget / std::max(lastLevel, 1u), 1u, p.leavesPerTwig);
  const float size = p.leafSizeM * std::min(scale, 1.0f) *
                     std::sqrt(static_cast<float>(p.leavesPerTwig) / static_cast<float>(perBranch));
  addCards(k, p, env, perBranch, size, rng);
  return k;
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
  const float crownBase = params.form == TreeForm::Conifer ? rng.range(0.22f, 0.3f) * heightM
                                                           : rng.range(0.35f, 0.45f) * heightM - 0.12f * heightM;
  const Envelope env{params.form, heightM, 0.5f * crownWidthM, crownBase};
  const float trunkRadius = params.trunkRadiusM * heightM / 10.0f;
  // The free-tip fit: within 1 % of the analytic beam for every taper the catalog allows (≤ 0.9).
  const BeamFit fit = fitTaperedBeamFreeTip(params.taper);

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
      for (const Card& c : lod == TreeLod::Full ? k.cards : reducedCards(k, env)) addCardQuad(mesh, c);
    }
    candidate.crownRadiusM = std::max(meshRadius(candidate.lod[0]), meshRadius(candidate.lod[1]));
    model = std::move(candidate);
    if (model.crownRadiusM <= 1.08f * env.radius) break;
    scale *= 1.04f * env.radius / model.crownRadiusM;
  }
  return model;
}

}  // namespace vegstream::vegetation
