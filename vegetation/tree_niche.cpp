// Tree species by colour and site (tree_niche.h): a softened environmental envelope (H. A. Nix,
// "A biogeographic analysis of Australian elapid snakes", 1986: BIOCLIM's ranges; J. Elith and
// J. R. Leathwick, Annu. Rev. Ecol. Evol. Syst. 40, 2009) added to the colour score's log (core
// seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16), the two best by eq. 17–18.
#include "vegetation/tree_niche.h"

#include <cassert>

namespace vegstream::vegetation {
namespace {

// −(distance of v outside [lo, hi] / soft)²; 0 inside or when v is unknown.
float rangeFit(float v, const float (&range)[2], float soft) {
  if (!std::isfinite(v)) return 0.0f;
  const float out = v < range[0] ? range[0] - v : v > range[1] ? v - range[1] : 0.0f;
  const float d = out / soft;
  return -d * d;
}

}  // namespace

float logNicheFit(const TreeNiche& niche, const TreeSite& site) {
  return rangeFit(site.elevationM, niche.elevationM, kElevationSoftM) +
         rangeFit(site.slopeDeg, niche.slopeDeg, kSlopeSoftDeg) + rangeFit(site.reliefM, niche.reliefM, kReliefSoftM);
}

SpeciesChoice chooseTreeSpecies(const SpeciesCatalog& catalog, int firstChoice, const GroundColour& ground, float ndvi,
                                const TreeSite& site, float z, SpeciesMask allowed) {
  int first = -1, second = -1;
  float l0 = 0.0f, l1 = 0.0f;
  for (size_t i = 0; i < catalog.species.size(); ++i) {
    const Species& s = catalog.species[i];
    const bool candidate = static_cast<int>(i) == firstChoice || (!s.tree.claimsGround && i < 32 && ((allowed >> i) & 1u));
    if (!isTree(s) || !candidate) continue;
    const float colour = logColourScore(s.score, ground.hsv, ndvi, ground.exg);
    if (!passesOwnThreshold(s, colour)) continue;
    const float l = kTreeColourShare * colour + logNicheFit(s.tree.niche, site);
    const int idx = static_cast<int>(i);
    if (first < 0 || l > l0) {  // strictly greater: of equals the lower index stays ahead
      second = first;
      l1 = l0;
      first = idx;
      l0 = l;
    } else if (second < 0 || l > l1) {
      second = idx;
      l1 = l;
    }
  }
  SpeciesChoice out;
  if (first < 0) return out;
  out.secondRatio = second >= 0 ? 1.0f / (1.0f + std::exp(l0 - l1)) : 0.0f;  // eq. 18's s1 / (s0 + s1)
  const bool takeSecond = z < out.secondRatio;
  out.species = takeSecond ? second : first;
  out.sPrime = takeSecond ? out.secondRatio : 1.0f - out.secondRatio;
  assert(out.species >= 0);
  return out;
}

}  // namespace vegstream::vegetation
