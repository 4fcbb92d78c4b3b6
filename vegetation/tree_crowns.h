#pragma once
// Internal to tree_model.cpp / tree_crowns.cpp (issue 20): the skeleton a tree model is grown as,
// its crown envelope, and the two crown recipes (conifer, broadleaf) with their cards. Not part
// of the vegetation library's interface (tree_model.h is).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "vegetation/philox.h"
#include "vegetation/tree_bending.h"
#include "vegetation/tree_model.h"

namespace vegstream::vegetation::tree_detail {

using glm::vec3;
inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kGoldenAngle = 2.39996323f;
inline constexpr uint32_t kRandomStream = 0x74726565u;  // "tree"
inline constexpr float kCrownRoundness = 2.5f;

class Random {
 public:
  explicit Random(uint32_t seed) : seed_(seed) {}
  float next() { return u01(philox(counter_++, kRandomStream, seed_).x); }
  float range(float lo, float hi) { return lo + (hi - lo) * next(); }
  // A uniformly distributed unit vector.
  vec3 unit() {
    const float z = range(-1.0f, 1.0f), a = range(0.0f, 2.0f * kPi), rho = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {rho * std::cos(a), rho * std::sin(a), z};
  }

 private:
  uint32_t seed_;
  uint32_t counter_ = 0;
};

inline vec3 load(const float (&a)[3]) { return {a[0], a[1], a[2]}; }
inline void store(float (&a)[3], vec3 v) { a[0] = v.x, a[1] = v.y, a[2] = v.z; }
inline float horizontal(vec3 p) { return std::sqrt(p.x * p.x + p.y * p.y); }
// Turns unit `axis` by `angle` towards unit `towards` (⟂ axis).
inline vec3 tilt(vec3 axis, vec3 towards, float angle) { return axis * std::cos(angle) + towards * std::sin(angle); }
inline vec3 pointOn(const TreeBranch& b, float x) { return load(b.origin) + load(b.t) * (x * b.length); }

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
// broadleaves a superellipsoid (exponent kCrownRoundness: fuller than an ellipsoid at the crown's
// shoulders and bottom, as a spreading crown is) from the crown base to the top.
struct Envelope {
  TreeForm form;
  float height, radius, base;

  float centreZ() const { return 0.5f * (base + height); }
  float halfHeight() const { return 0.5f * (height - base); }
  // The broadleaf crown's surface in the direction (cos el, sin el) from its centre: the factor
  // on (radius cos el, halfHeight sin el).
  static float shellScale(float cosEl, float sinEl) {
    return std::pow(std::pow(std::abs(cosEl), kCrownRoundness) + std::pow(std::abs(sinEl), kCrownRoundness),
                    -1.0f / kCrownRoundness);
  }
  // The conifer cone's radius at height z.
  float coneRadius(float z) const { return radius * std::clamp((height - z) / (height - base), 0.0f, 1.0f); }
  bool inside(vec3 p) const {
    if (p.z > height || p.z < 0.0f) return false;
    const float rho = horizontal(p);
    if (form == TreeForm::Conifer) return rho <= coneRadius(p.z);
    const float a = rho / radius, b = std::abs(p.z - centreZ()) / halfHeight();
    return std::pow(a, kCrownRoundness) + std::pow(b, kCrownRoundness) <= 1.0f;
  }
  // How far from p along unit d until the envelope is left (0 if p is outside).
  float reach(vec3 p, vec3 d) const {
    if (!inside(p)) return 0.0f;
    const float step = 0.05f * (height + radius);
    float lo = 0.0f, hi = step;
    while (inside(p + d * hi) && hi < 4.0f * (height + radius)) lo = hi, hi += step;
    for (int i = 0; i < 16; ++i) {
      const float mid = 0.5f * (lo + hi);
      (inside(p + d * mid) ? lo : hi) = mid;
    }
    return lo;
  }
};

inline float radiusAt(const Skeleton& k, uint32_t b, float x, float taper) {
  return k.rootRadius[b] * (1.0f + (taper - 1.0f) * x);
}

uint32_t addBranch(Skeleton& k, int32_t parent, float parentAlong, vec3 direction, float length, float rootRadius,
                   const BeamFit& fit);

// The crowns (tree_crowns.cpp): level-1 and level-2 branches, level-3 branchlets, and the Full
// cards — `total` spread evenly over the last-level branches (at most leavesPerTwig on one), on
// their outer part, each about `size` long.
void growConifer(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng, const BeamFit& fit);
void growBroadleaf(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng,
                   const BeamFit& fit);
void growBranchlets(Skeleton& k, const TreeParams& p, const Envelope& env, float scale, Random& rng,
                    const BeamFit& fit);
void addCards(Skeleton& k, const TreeParams& p, const Envelope& env, uint32_t total, float size, Random& rng);
// The crown envelope's side view, m²: what the cards must fill.
float sideArea(const Envelope& env);
// A card's area for its length (conifer sprays are 0.6 as wide as long, leaf clumps about square).
float cardArea(TreeForm form, float length);
// Keeps a card under the top and inside the crown's width (5 % slack).
void fitCard(Card& c, const Envelope& env);

}  // namespace vegstream::vegetation::tree_detail
