// The two crown recipes of issue 20's procedural trees (tree_model.cpp builds the meshes). Both
// fill a crown envelope: the model is seen from 20–300 m, where what counts is a crown whose
// side view is mostly filled out to the asked width, so the cards are large (needle sprays and
// leaf clumps of about a metre) and hang on branches that reach the envelope.
//
// Conifer (ponderosa pine, white fir, Douglas fir): one leader to the top; whorls of level-1
// branches from the crown base (22–32 % of the height) to near the top, at branchAngleDeg from the
// axis, drooping more the lower they are, each reaching 80–100 % of the way to the cone (less a
// card's overhang) so the crown has a slightly ragged edge; level-2 twigs alternately left and
// right in a flat, slightly drooping spray. Needle cards along the twigs, oriented at random
// (biased up and out) so the cone is filled from every side and from above; near the top they
// shrink with the cone so it ends in a point.
//
// Broadleaf (cottonwood, box elder, live oak): a short trunk (30–40 % of the height) forking into
// 3–6 thick limbs that rise at branchAngleDeg and reach about 55 % of the way to the crown
// envelope (a superellipsoid); each limb's twigs run from it to points on the envelope's outer shell in that limb's
// sector (all elevations, a few below the fork), so leaf clusters fill the whole round crown;
// level-3 branchlets, when asked, fan out around each twig. Leaf cards face out from the crown's
// centre, jittered.
#include <algorithm>
#include <cassert>
#include <cmath>

#include "vegetation/tree_crowns.h"

namespace vegstream::vegetation::tree_detail {
namespace {

// A child's root radius: thinner than its parent there and slender, at least `slenderness`:1.
float childRadius(const Skeleton& k, uint32_t parent, float x, float length, float taper, float share = 0.6f,
                  float slenderness = 35.0f) {
  return std::max(0.002f, std::min(share * radiusAt(k, parent, x, taper), length / slenderness));
}

vec3 orthogonalTo(vec3 v, vec3 axis, vec3 fallback) {
  v -= axis * glm::dot(v, axis);
  return glm::length(v) > 1e-3f ? glm::normalize(v) : fallback;
}

vec3 anyPerpendicular(vec3 a) {
  return glm::normalize(glm::cross(a, std::abs(a.z) < 0.9f ? vec3(0.0f, 0.0f, 1.0f) : vec3(1.0f, 0.0f, 0.0f)));
}

}  // namespace

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

void growConifer(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng, const BeamFit& fit) {
  const float H = env.height;
  const uint32_t perWhorl = p.branches >= 30 ? 5u : p.branches >= 12 ? 4u : 3u;
  const uint32_t whorls = (p.branches + perWhorl - 1) / perWhorl;
  const float angle = p.branchAngleDeg * kPi / 180.0f;
  const float span = 0.97f * H - env.base;
  const float overhang = 0.35f * p.leafSizeM;  // the cards reach past the twigs
  for (uint32_t i = 0; i < p.branches; ++i) {
    const uint32_t w = i / perWhorl;
    const float h = (static_cast<float>(w) + rng.range(0.0f, 0.7f)) / static_cast<float>(whorls);  // 0: crown base
    const float z = env.base + span * h;
    const float azimuth = kGoldenAngle * static_cast<float>(w) +
                          2.0f * kPi * static_cast<float>(i % perWhorl) / static_cast<float>(perWhorl) +
                          rng.range(-0.35f, 0.35f);
    // Low branches droop, the top ones rise.
    const float theta = std::clamp(angle + 0.35f * (1.0f - h) - 0.3f * h * h + rng.range(-0.08f, 0.08f), 0.35f, 2.0f);
    const vec3 out(std::cos(azimuth), std::sin(azimuth), 0.0f);
    const vec3 d = tilt(vec3(0.0f, 0.0f, 1.0f), out, theta);
    const float wanted = scale * env.coneRadius(z) * rng.range(0.8f, 1.0f) - overhang;
    float length = std::max(0.15f, wanted) / std::sin(theta);
    length = std::min(length, 0.95f * z / std::max(0.05f, -d.z));  // not into the ground
    const float x = z / H;
    const uint32_t b = addBranch(k, 0, x, d, length, childRadius(k, 0, x, length, p.taper), fit);
    for (uint32_t j = 0; j < p.twigs; ++j) {
      const TreeBranch& parent = k.branches[b];
      const float along = 0.12f + 0.83f * (static_cast<float>(j) + rng.range(0.2f, 0.8f)) / static_cast<float>(p.twigs);
      const float side = (j % 2 == 0) ? 1.0f : -1.0f;
      const vec3 twigDir = glm::normalize(tilt(load(parent.t), load(parent.r) * side, rng.range(0.6f, 1.0f)) -
                                          vec3(0.0f, 0.0f, rng.range(0.0f, 0.25f)));
      const float twigLength =
          std::max(0.15f, 0.42f * parent.length * (1.0f - 0.55f * along) * rng.range(0.85f, 1.15f));
      addBranch(k, static_cast<int32_t>(b), along, twigDir, twigLength, childRadius(k, b, along, twigLength, p.taper),
                fit);
    }
  }
}

void growBroadleaf(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng,
                   const BeamFit& fit) {
  const uint32_t limbs = std::clamp(p.branches, 3u, 6u);
  const float angle = p.branchAngleDeg * kPi / 180.0f;
  const float turn = rng.range(0.0f, 2.0f * kPi);
  const vec3 centre(0.0f, 0.0f, env.centreZ());
  for (uint32_t i = 0; i < limbs; ++i) {
    const float azimuth =
        turn + 2.0f * kPi * static_cast<float>(i) / static_cast<float>(limbs) + rng.range(-0.3f, 0.3f);
    const vec3 out(std::cos(azimuth), std::sin(azimuth), 0.0f);
    // One limb of four or more carries on as a leader, the others spread.
    const float theta = (i == 0 && limbs >= 4 ? 0.35f : 1.0f) * angle + rng.range(-0.15f, 0.15f);
    const vec3 d = tilt(vec3(0.0f, 0.0f, 1.0f), out, theta);
    const float x = rng.range(0.86f, 1.0f);
    const vec3 origin = pointOn(k.branches[0], x);
    const float length = std::max(0.3f, 0.55f * scale * env.reach(origin, d) * rng.range(0.9f, 1.05f));
    const uint32_t b = addBranch(k, 0, x, d, length, childRadius(k, 0, x, length, p.taper, 0.75f, 14.0f), fit);
    for (uint32_t j = 0; j < p.twigs; ++j) {
      const TreeBranch& limb = k.branches[b];
      const float along = 0.25f + 0.75f * (static_cast<float>(j) + rng.range(0.2f, 0.8f)) / static_cast<float>(p.twigs);
      const vec3 twigOrigin = pointOn(limb, along);
      // A point on the crown's outer shell in this limb's sector.
      const float az = azimuth + rng.range(-1.15f, 1.15f) * kPi / static_cast<float>(limbs);
      const float sinEl = rng.range(-0.45f, 0.95f), cosEl = std::sqrt(1.0f - sinEl * sinEl);
      const float shell = scale * rng.range(0.72f, 0.9f) * Envelope::shellScale(cosEl, sinEl);
      const vec3 target = centre + vec3(env.radius * shell * cosEl * std::cos(az),
                                        env.radius * shell * cosEl * std::sin(az), env.halfHeight() * shell * sinEl);
      vec3 dir = target - twigOrigin;
      float twigLength = glm::length(dir);
      if (twigLength < 0.3f) dir = load(limb.t), twigLength = 0.3f;
      addBranch(k, static_cast<int32_t>(b), along, dir, twigLength,
                childRadius(k, b, along, twigLength, p.taper, 0.6f, 30.0f), fit);
    }
  }
}

void growBranchlets(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng,
                    const BeamFit& fit) {
  const bool conifer = p.form == TreeForm::Conifer;
  const uint32_t perTwig = std::max(2u, p.twigs / 2);
  const size_t twigs = k.branches.size();
  for (size_t i = 0; i < twigs; ++i) {
    if (k.branches[i].level != 2) continue;
    for (uint32_t j = 0; j < perTwig; ++j) {
      const TreeBranch& twig = k.branches[i];
      const float along = 0.3f + 0.65f * (static_cast<float>(j) + rng.range(0.2f, 0.8f)) / static_cast<float>(perTwig);
      // Conifers: a flat spray, left and right; broadleaves: all around the twig.
      const float around = conifer ? (j % 2 == 0 ? 0.0f : kPi) : kGoldenAngle * static_cast<float>(j) + rng.range(0.0f, 6.3f);
      const vec3 sideways = load(twig.r) * std::cos(around) + load(twig.s) * std::sin(around);
      const vec3 dir = glm::normalize(tilt(load(twig.t), sideways, rng.range(0.5f, 0.9f)));
      const vec3 origin = pointOn(twig, along);
      const float reach = std::max(env.reach(origin, dir), 0.1f);
      const float length = std::clamp(std::min(0.5f * twig.length, 0.9f * scale * reach), 0.1f, twig.length);
      addBranch(k, static_cast<int32_t>(i), along, dir, length,
                childRadius(k, static_cast<uint32_t>(i), along, length, p.taper), fit);
    }
  }
}

void fitCard(Card& c, const Envelope& env) {
  for (int i = 0; i < 6; ++i) {
    const vec3 across = glm::cross(c.axis, c.normal) * (0.5f * c.width);
    const vec3 tip = c.stem + c.axis * c.length;
    bool fits = true;
    for (vec3 q : {c.stem - across, c.stem + across, tip - across, tip + across})
      fits = fits && q.z <= env.height && q.z >= 0.0f && horizontal(q) <= 1.05f * env.radius;
    if (fits) return;
    if (i == 0 && tip.z > env.height && c.axis.z > 0.0f) {
      c.axis.z = -c.axis.z;
      const vec3 normal = c.normal - c.axis * glm::dot(c.normal, c.axis);
      if (glm::length(normal) > 1e-3f)
        c.normal = glm::normalize(normal);
      else
        c.axis.z = -c.axis.z;  // keep the old, consistent frame
    } else {
      c.length *= 0.75f, c.width *= 0.85f;
    }
  }
}

float sideArea(const Envelope& env) {
  if (env.form == TreeForm::Conifer) return env.radius * (env.height - env.base);  // a triangle
  // A superellipse's area: 4ab Γ(1 + 1/n)² / Γ(1 + 2/n).
  const float n = kCrownRoundness;
  return 4.0f * env.radius * env.halfHeight() * std::pow(std::tgamma(1.0f + 1.0f / n), 2.0f) /
         std::tgamma(1.0f + 2.0f / n);
}

float cardArea(TreeForm form, float length) { return (form == TreeForm::Conifer ? 0.6f : 0.92f) * length * length; }

void addCards(Skeleton& k, const TreeParams& p, const Envelope& env, uint32_t total, float size, Random& rng) {
  const bool conifer = p.form == TreeForm::Conifer;
  const vec3 centre(0.0f, 0.0f, env.centreZ());
  const size_t count = k.branches.size();
  uint32_t last = 0;
  for (const TreeBranch& b : k.branches) last += b.level == p.branchLevels ? 1u : 0u;
  uint32_t seen = 0;
  for (size_t i = 0; i < count; ++i) {
    const TreeBranch& b = k.branches[i];
    if (b.level != p.branchLevels) continue;
    // This branch's share of the total, spread evenly (some branches get one more).
    const auto before = static_cast<uint32_t>(uint64_t{seen} * total / std::max(last, 1u));
    ++seen;
    const auto upTo = static_cast<uint32_t>(uint64_t{seen} * total / std::max(last, 1u));
    const uint32_t perBranch = std::min(upTo - before, p.leavesPerTwig);
    for (uint32_t j = 0; j < perBranch; ++j) {
      // On the branch's outer half, where the crown's surface is: cards deep inside are hidden
      // behind the others yet still cost their pixels.
      const float share = (static_cast<float>(j) + rng.range(0.1f, 0.9f)) / static_cast<float>(perBranch);
      const float along = conifer ? 0.4f + 0.6f * share : 0.45f + 0.55f * share;
      Card c{};
      c.stem = pointOn(b, along);
      const vec3 out = horizontal(c.stem) > 1e-3f ? glm::normalize(vec3(c.stem.x, c.stem.y, 0.0f)) : load(b.r);
      vec3 facing;
      if (conifer) {
        // Needle sprays at random, a little up and out: the cone is filled from every side.
        facing = rng.unit() + vec3(0.0f, 0.0f, 0.35f) + 0.3f * out;
      } else {
        // Leaf clumps facing out of the crown, jittered.
        const vec3 fromCentre = c.stem - centre;
        facing = (glm::length(fromCentre) > 1e-3f ? glm::normalize(fromCentre) : out) + 0.9f * rng.unit() +
                 vec3(0.0f, 0.0f, 0.2f);
      }
      if (glm::length(facing) < 1e-3f) facing = out;
      c.normal = glm::normalize(facing);
      // The card's axis: along its branch (sprays droop), ⟂ the normal.
      const vec3 lean = conifer ? load(b.t) + vec3(0.0f, 0.0f, rng.range(-0.7f, 0.1f)) + 0.4f * rng.unit()
                                : load(b.t) + 0.8f * rng.unit() + vec3(0.0f, 0.0f, 0.25f);
      c.axis = orthogonalTo(lean, c.normal, anyPerpendicular(c.normal));
      float length = size * rng.range(0.8f, 1.2f);
      if (conifer) length = std::min(length, std::max(0.3f * size, 1.6f * env.coneRadius(c.stem.z)));  // the point
      c.length = length;
      c.width = conifer ? 0.6f * c.length : c.length * rng.range(0.85f, 1.0f);
      // The card's middle on the branch, not its stem: clusters, not fringes.
      c.stem -= c.axis * ((conifer ? 0.2f : 0.4f) * c.length);
      c.branch = static_cast<uint32_t>(i);
      c.along = along;
      fitCard(c, env);
      k.cards.push_back(c);
    }
  }
}

}  // namespace vegstream::vegetation::tree_detail
