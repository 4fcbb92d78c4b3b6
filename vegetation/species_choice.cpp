// Species choice, core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16–18. Plain
// float maths in the order species_choice.h documents, so the GLSL twin gives the same choice.
#include "vegetation/species_choice.h"

#include <algorithm>
#include <cmath>

namespace vegstream::vegetation {

bool passesThreshold(const Species& s, float logScore) {
  if (isTree(s) && !s.tree.claimsGround) return false;  // only among the trees (tree_niche.h)
  return passesOwnThreshold(s, logScore);
}

bool passesOwnThreshold(const Species& s, float logScore) {
  // s ≥ t ⇔ ln s ≥ ln t: compared as logs because s itself overflows float for large p.
  return !(s.threshold > 0.0f) || !(logScore < std::log(s.threshold));
}

SpeciesCandidates speciesCandidatesAt(const SpeciesCatalog& catalog, glm::vec3 linear, float ndvi,
                                      SpeciesMask allowed) {
  const GroundColour g = calibratedGround(catalog.calibration, linear);
  return speciesCandidates(catalog, g.hsv, ndvi, g.exg, allowed);
}

SpeciesChoice chooseSpeciesAt(const SpeciesCatalog& catalog, glm::vec3 linear, float z, float ndvi,
                              SpeciesMask allowed) {
  const GroundColour g = calibratedGround(catalog.calibration, linear);
  return chooseSpecies(catalog, g.hsv, z, ndvi, g.exg, allowed);
}

SpeciesCandidates speciesCandidates(const SpeciesCatalog& catalog, glm::vec3 hsv, float ndvi, float exg,
                                    SpeciesMask allowed) {
  SpeciesCandidates c;
  for (size_t i = 0; i < catalog.species.size(); ++i) {
    if (((allowed >> i) & 1u) == 0u) continue;  // the landcover class does not allow it
    const Species& s = catalog.species[i];
    const float l = logColourScore(s.score, hsv, ndvi, exg);
    if (!passesThreshold(s, l)) continue;
    const int idx = static_cast<int>(i);
    // Strictly greater: of equal scores the lower index stays ahead.
    if (c.first < 0 || l > c.logFirst) {
      c.second = c.first;
      c.logSecond = c.logFirst;
      c.first = idx;
      c.logFirst = l;
    } else if (c.second < 0 || l > c.logSecond) {
      c.second = idx;
      c.logSecond = l;
    }
  }
  // s1 / (s0 + s1) = 1 / (1 + s0 / s1) = 1 / (1 + exp(l0 − l1)); exp(large) = inf gives 0.
  if (c.second >= 0) c.secondRatio = 1.0f / (1.0f + std::exp(c.logFirst - c.logSecond));
  return c;
}

SpeciesChoice chooseSpecies(const SpeciesCatalog& catalog, glm::vec3 hsv, float z, float ndvi, float exg,
                            SpeciesMask allowed) {
  return chooseAmong(catalog, speciesCandidates(catalog, hsv, ndvi, exg, allowed), z);
}

float canopyCoverOf(const SpeciesCatalog& catalog, const SpeciesCandidates& c) {
  const auto tree = [&](int s) { return s >= 0 && isTree(catalog.species[static_cast<size_t>(s)]); };
  return (tree(c.first) ? 1.0f - c.secondRatio : 0.0f) + (tree(c.second) ? c.secondRatio : 0.0f);
}

SpeciesChoice chooseAmong(const SpeciesCatalog& catalog, const SpeciesCandidates& c, float z) {
  SpeciesChoice out;
  if (c.first < 0) return out;  // nothing scores: rejected
  out.secondRatio = c.secondRatio;
  const bool second = z < c.secondRatio;  // eq. 18; never true when only one is in (ratio 0)
  const int picked = second ? c.second : c.first;
  out.sPrime = second ? c.secondRatio : 1.0f - c.secondRatio;
  if (catalog.species[static_cast<size_t>(picked)].bare) {
    out.species = -1;  // bare soil: the seed grows nothing
    return out;
  }
  out.species = picked;
  return out;
}

float treeStandShare(float sPrime) {
  const float t = std::clamp((sPrime - kStandShareLo) / (kStandShareHi - kStandShareLo), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

SpeciesChoice choosePlantSpeciesAt(const SpeciesCatalog& catalog, glm::vec3 linear, float z, float ndvi,
                                   SpeciesMask allowed) {
  const GroundColour g = calibratedGround(catalog.calibration, linear);
  return choosePlantSpecies(catalog, g.hsv, z, ndvi, g.exg, allowed);
}

SpeciesChoice choosePlantSpecies(const SpeciesCatalog& catalog, glm::vec3 hsv, float z, float ndvi, float exg,
                                 SpeciesMask allowed) {
  const SpeciesCandidates c = speciesCandidates(catalog, hsv, ndvi, exg, allowed);
  SpeciesChoice out;
  if (c.first < 0) return out;
  out.secondRatio = c.secondRatio;
  const bool second = z < c.secondRatio;
  int picked = second ? c.second : c.first;
  const int other = second ? c.first : c.second;
  out.sPrime = second ? c.secondRatio : 1.0f - c.secondRatio;
  const float u = second ? z / c.secondRatio : (z - c.secondRatio) / (1.0f - c.secondRatio);
  const auto treeOrBare = [&](int s) {
    const Species& sp = catalog.species[static_cast<size_t>(s)];
    return sp.bare || isTree(sp);
  };
  if (isTree(catalog.species[static_cast<size_t>(picked)])) {
    if (other < 0 || u < treeStandShare(out.sPrime)) return {-1, out.sPrime, out.secondRatio};  // forest floor
    picked = other;
    out.sPrime = 1.0f - out.sPrime;
  }
  out.species = treeOrBare(picked) ? -1 : picked;
  return out;
}

}  // namespace vegstream::vegetation
