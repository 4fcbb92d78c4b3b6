// A tree crown's opaque core (issue 20; the "inner shell" of production foliage): a closed,
// low-polygon solid of revolution inside the crown, drawn before the cards with depth tests early
// and no alpha test. It is what the eye sees through the gaps between needle sprays and leaf
// clumps deep in a crown (dark foliage in its own shade), so a handful of card layers reads as a
// dense crown; and the depth it writes first lets the hardware reject the cards behind it before
// shading them, where a crown of alpha-tested cards alone is rasterised layer by layer (on the
// H200 each layer kept costs its pixels: render/README.md "Trees").
//
// Its shape follows the cards actually grown, not the nominal envelope (a sparse crown's branches
// stop short of it, and a few branches make it far from round): in each of kBands height bands of
// the cards, a ring whose vertex in each of kCoreSides sectors of azimuth is at kShare of the
// kQuantile-th horizontal distance of the card corners in that band and sector.
#include "vegetation/tree_core.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <vector>

namespace vegstream::vegetation::tree_detail {
namespace {

constexpr int kBands = 6;
constexpr float kQuantile = 0.5f;
constexpr float kShare = 0.8f;

}  // namespace

CrownCore crownCoreOf(const TreeMesh& mesh) {
  float zLo = 1e30f, zHi = -1e30f;
  for (const TreeVertex& v : mesh.vertices)
    if (v.kind == 1) zLo = std::min(zLo, v.position[2]), zHi = std::max(zHi, v.position[2]);
  CrownCore core;
  if (!(zHi > zLo)) return core;  // no cards
  const float band = (zHi - zLo) / kBands;
  // Per band and sector of azimuth (sector s about the ring's vertex s: a crown of few branches
  // is far from round).
  std::vector<std::vector<float>> distances(size_t{kBands} * kCoreSides);
  for (const TreeVertex& v : mesh.vertices) {
    if (v.kind != 1) continue;
    const int b = std::clamp(static_cast<int>((v.position[2] - zLo) / band), 0, kBands - 1);
    const float turns = std::atan2(v.position[1], v.position[0]) / (2.0f * kPi) + 1.0f;
    const auto s = static_cast<uint32_t>(std::lround(turns * kCoreSides)) % kCoreSides;
    distances[size_t(b) * kCoreSides + s].push_back(std::hypot(v.position[0], v.position[1]));
  }
  for (int b = 0; b < kBands; ++b) {
    CrownCore::Ring ring{zLo + (static_cast<float>(b) + 0.5f) * band, {}};
    bool enough = true;
    for (uint32_t s = 0; s < kCoreSides && enough; ++s) {
      std::vector<float>& d = distances[size_t(b) * kCoreSides + s];
      enough = d.size() >= 4;  // too few card corners here to stand for foliage
      if (!enough) break;
      const auto at = d.begin() + static_cast<std::ptrdiff_t>(kQuantile * static_cast<float>(d.size() - 1));
      std::nth_element(d.begin(), at, d.end());
      // ±12 % from ring to ring and side to side (a fixed pattern): a core's outline as ragged as
      // foliage, not a turned cone, where it shows between the cards.
      const float jitter = 0.88f + 0.24f * u01(philox(static_cast<uint32_t>(b) * kCoreSides + s, kRandomStream, 0x636f7265u).x);
      ring.radiusM[s] = kShare * *at * jitter;
    }
    if (enough) core.rings.push_back(ring);
  }
  if (core.rings.size() < 2) core.rings.clear();
  return core;
}

void addCrownCore(TreeMesh& mesh, const CrownCore& core, float trunkLength) {
  assert(trunkLength > 0.0f);
  mesh.coreFirstIndex = static_cast<uint32_t>(mesh.indices.size());
  if (core.rings.empty()) return;
  const auto first = static_cast<uint32_t>(mesh.vertices.size());
  const auto rings = static_cast<uint32_t>(core.rings.size());
  auto add = [&](vec3 p, vec3 n) {
    TreeVertex v{};
    store(v.position, p);
    store(v.normal, glm::normalize(n));
    v.branch = 0;  // it sways with the trunk
    v.along = std::clamp(p.z / trunkLength, 0.0f, 1.0f);
    v.kind = 2;
    mesh.vertices.push_back(v);
  };
  for (uint32_t r = 0; r < rings; ++r) {
    // The side's normal from the profile's slope about this ring (dr/dz outward is −slope in z).
    const CrownCore::Ring& below = core.rings[r > 0 ? r - 1 : r];
    const CrownCore::Ring& above = core.rings[r + 1 < rings ? r + 1 : r];
    for (uint32_t s = 0; s < kCoreSides; ++s) {
      const float slope = (above.radiusM[s] - below.radiusM[s]) / std::max(above.z - below.z, 1e-3f);
      const float a = 2.0f * kPi * static_cast<float>(s) / kCoreSides;
      const vec3 dir(std::cos(a), std::sin(a), 0.0f);
      add(dir * core.rings[r].radiusM[s] + vec3(0.0f, 0.0f, core.rings[r].z), dir + vec3(0.0f, 0.0f, -slope));
    }
  }
  // Closed by a point under the lowest ring and one over the highest, a quarter of a band out.
  const float half = 0.5f * (core.rings.back().z - core.rings.front().z) / static_cast<float>(rings - 1);
  const auto bottom = static_cast<uint32_t>(mesh.vertices.size());
  add({0.0f, 0.0f, core.rings.front().z - 0.5f * half}, {0.0f, 0.0f, -1.0f});
  const auto top = static_cast<uint32_t>(mesh.vertices.size());
  add({0.0f, 0.0f, core.rings.back().z + 0.5f * half}, {0.0f, 0.0f, 1.0f});
  // Outward-facing: counter-clockwise seen from outside.
  for (uint32_t s = 0; s < kCoreSides; ++s) {
    const uint32_t next = (s + 1) % kCoreSides;
    mesh.indices.insert(mesh.indices.end(), {bottom, first + next, first + s});
    for (uint32_t r = 0; r + 1 < rings; ++r) {
      const uint32_t a = first + r * kCoreSides + s, b = first + r * kCoreSides + next;
      const uint32_t c = a + kCoreSides, d = b + kCoreSides;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
    const uint32_t last = first + (rings - 1) * kCoreSides;
    mesh.indices.insert(mesh.indices.end(), {top, last + s, last + next});
  }
}

}  // namespace vegstream::vegetation::tree_detail
