#pragma once
// Species choice from the imagery colour under a plant, core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16–18: every species scores the base
// colour (eq. 16), the two best compete, and a uniform random z picks one of them with
// probability proportional to its score (eq. 17–18); the winner's s′ (its share of the two)
// later scales the plant, so plants thin out towards the border of their colour region.
//
// The GLSL twin (render/classify, written against this) must follow chooseSpecies operation for
// operation; its float operations, in order, per species i (index order 0, 1, …):
//   l_i = logColourScore(score_i, hsv, ndvi, exg)      (colour_score.h: −p · log(max(dist, 1e-4)))
//   out when threshold_i > 0 and l_i < log(threshold_i)   (log(threshold) is the only other log)
//   best two by strictly greater l: a tie keeps the lower index first (l0 ≥ l1)
// then, with d = l0 − l1 ≥ 0 (one species in: ratio = 0):
//   ratio = 1 / (1 + exp(d))                          = s1 / (s0 + s1), never overflows to NaN
//   z < ratio → the second, s′ = ratio;  else the first, s′ = 1 − ratio     (eq. 18)
// and a bare-soil winner → species −1 (the seed is rejected), as is "no species in".
// `allowed` (landcover_species.h, issue 41): species i takes part only where bit i is set, tested
// before its score (GLSL: `(allowed >> i) & 1u`); kAllSpecies where the dataset has no landcover
// (then the choice is exactly what it was without the mask).

#include <glm/vec3.hpp>

#include "vegetation/species_catalog.h"

namespace vegstream::vegetation {

struct SpeciesChoice {
  int species = -1;          // index into the catalog; −1: rejected (bare soil or nothing scores)
  float sPrime = 0.0f;       // the chosen one's share s / (s0 + s1) of the two best (eq. 18)
  float secondRatio = 0.0f;  // s1 / (s0 + s1): the probability of the second best (0: one in)
};

// The two best species at one base colour, before z decides (for `query` and the tests).
struct SpeciesCandidates {
  int first = -1, second = -1;              // catalog indices (bare included); −1: none in
  float logFirst = 0.0f, logSecond = 0.0f;  // their log scores l0 ≥ l1
  float secondRatio = 0.0f;                 // s1 / (s0 + s1), 0 when fewer than two are in
};

// Whether species `s` takes part at log score `logScore` (its threshold, eq. 16 score s ≥ t). A
// tree species that does not claim ground (TreeParams::claimsGround) never does: it grows only
// among the trees (tree_niche.h); the GPU twin sees its threshold as +∞ (render/classify_layout).
bool passesThreshold(const Species& s, float logScore);
// The threshold alone, claimsGround aside (the choice among the trees).
bool passesOwnThreshold(const Species& s, float logScore);

// From the imagery's linear colour under a point: the catalog's calibration applied
// (colour_calibration.h), HSV and ExG of the result, then the choice below with both.
SpeciesCandidates speciesCandidatesAt(const SpeciesCatalog& catalog, glm::vec3 linear, float ndvi = kNoNdvi,
                                      SpeciesMask allowed = kAllSpecies);
SpeciesChoice chooseSpeciesAt(const SpeciesCatalog& catalog, glm::vec3 linear, float z, float ndvi = kNoNdvi,
                              SpeciesMask allowed = kAllSpecies);

// `ndvi`: the NDVI under the point, kNoNdvi (or NaN) where the dataset has none (colour_score.h);
// `exg`: its excess green, kNoExg leaves the term out (callers that only have HSV).
SpeciesCandidates speciesCandidates(const SpeciesCatalog& catalog, glm::vec3 hsv, float ndvi = kNoNdvi,
                                    float exg = kNoExg, SpeciesMask allowed = kAllSpecies);

// z uniform in [0, 1) (u01 of a Philox word). Eq. 16–18 as described above.
SpeciesChoice chooseSpecies(const SpeciesCatalog& catalog, glm::vec3 hsv, float z, float ndvi = kNoNdvi,
                            float exg = kNoExg, SpeciesMask allowed = kAllSpecies);

// The imagery's canopy cover at a colour: the share of the two best (eq. 17–18) that are tree
// species — both trees: 1, neither: 0, one: its share. A 30 m pixel of closed forest scores the
// forest's colour (cover near 1), a meadow with scattered trees gives the trees the share its
// colour leans their way. Tree placement stands trees by it and closes their crowns by it
// (tree_placement.h); `query` reports it (canopy_cover).
float canopyCoverOf(const SpeciesCatalog& catalog, const SpeciesCandidates& c);

// z's choice between two candidates already scored (eq. 18; chooseSpecies = speciesCandidates,
// then this).
SpeciesChoice chooseAmong(const SpeciesCatalog& catalog, const SpeciesCandidates& c, float z);

// Where the colour's choice is a tree species, how likely a tree stands there, from the trees'
// share of the two best (s′ of the tree where the other is not a tree; tree placement passes
// canopyCoverOf, which is the same there and 1 where both are trees):
// smoothstep(kStandShareLo, kStandShareHi, share). Eq. 18 lets the second best win
// with its share — which scatters plants nicely at a border, but would stand a tree in every
// sixth cell of a meadow whose colour gives the forest a 15 % share. Trees stand where the colour
// clearly says forest (tree_placement.h); elsewhere the ground keeps its plants
// (choosePlantSpecies). GLSL twin: treeStandShare in species_choice.glsl.
inline constexpr float kStandShareLo = 0.25f, kStandShareHi = 0.75f;
float treeStandShare(float sPrime);

// The plants' choice (plant_seeding.h), whose trees grow on their own grid: chooseSpecies, and
// where it picks a tree species the seed is forest floor (rejected) with the probability the tree
// stands there (treeStandShare(s′)); else it takes the other of the two best, with share 1 − s′
// (rejected when there is none or it is bare or a tree too). That draw is z's place within the
// interval eq. 18 chose — z / ratio, or (z − ratio) / (1 − ratio) — uniform, with no new word.
// GLSL twin: choosePlantSpecies in species_choice.glsl, operation for operation.
SpeciesChoice choosePlantSpeciesAt(const SpeciesCatalog& catalog, glm::vec3 linear, float z, float ndvi = kNoNdvi,
                                   SpeciesMask allowed = kAllSpecies);
SpeciesChoice choosePlantSpecies(const SpeciesCatalog& catalog, glm::vec3 hsv, float z, float ndvi, float exg,
                                 SpeciesMask allowed);

// A mask where the ExG belongs would convert silently to float: refused at compile time.
SpeciesCandidates speciesCandidates(const SpeciesCatalog&, glm::vec3, float, SpeciesMask) = delete;
SpeciesChoice chooseSpecies(const SpeciesCatalog&, glm::vec3, float, float, SpeciesMask) = delete;

}  // namespace vegstream::vegetation
