#pragma once
// Where on the terrain each tree species belongs (issue 41 item 4): its niche in elevation, slope
// and relief, and the choice among the tree species that uses it. Core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 chooses a species by its colour score alone
// (eq. 16–18); this adds the site, as species-distribution models do with their environmental
// envelopes (the "BIOCLIM" envelope of H. A. Nix, 1986, softened: a Gaussian fall-off outside the
// range instead of a hard edge, as in J. Elith and J. R. Leathwick, "Species distribution models",
// Annu. Rev. Ecol. Evol. Syst. 40, 2009, §"Model types").
//
// Two stages, so the GPU's plant seeding stays the colour choice it is: (1) chooseSpecies over the
// whole catalog decides whether a point is a tree at all (the GPU makes the same decision for the
// plants, rejecting a seed whose winner is a tree); (2) where it is, chooseTreeSpecies lets the
// species that share the ground of others (claims_ground false) compete with that winner — the
// winner and those species only: between two species that claim ground the colour has decided —
// by
//
//     l_i = kTreeColourShare · ln s_i (eq. 16, colour and NDVI)  +  Σ_k −((distance of site_k outside range_k) / soft_k)²
//
// over the species whose colour passes their threshold, the two best competing by eq. 17–18 with
// its own uniform z. The site terms: elevation above mean sea level, slope
// and relief, the ground's height minus the mean of a ring kReliefRadiusM around it (negative in
// hollows and valley floors, positive on ridges). The soft widths, 50 m, 3° and 1.5 m, make a
// niche nearly a hard range beyond twice them (a 100 m miss costs as much as a colour twice as far
// from the reference at p = 6; colour log scores of forest colours differ by a few units). A term whose site value is unknown
// (NaN: no heights around the point) counts 0, as does a species without a niche.
//
// Catalog (a tree species' "tree" object, species_catalog.h): "niche": { "elevation_m": [lo, hi],
// "slope_deg": [lo, hi], "relief_m": [lo, hi] }, each optional, either end null for open, lo ≤ hi.

#include <cmath>
#include <limits>

#include <glm/vec3.hpp>

#include "vegetation/landcover_species.h"
#include "vegetation/species_choice.h"

namespace vegstream::vegetation {

inline constexpr double kReliefRadiusM = 75.0;  // the ring the relief is measured against
inline constexpr float kElevationSoftM = 50.0f, kSlopeSoftDeg = 3.0f, kReliefSoftM = 1.5f;
// The colour's share in the choice among the trees: the forest's colour already made the point a
// tree (stage 1); between tree species it only nudges, the site decides. At 1 the colour ruled:
// on the Kolob plateau 74 % of 1462 trees in 9 ha came out as aspen, whose reference happened to
// lie nearer the forest's colour than the pines' (measured before this share).
inline constexpr float kTreeColourShare = 0.25f;

// The site of a point; NaN where unknown.
struct TreeSite {
  float elevationM = std::numeric_limits<float>::quiet_NaN();  // above mean sea level
  float slopeDeg = std::numeric_limits<float>::quiet_NaN();    // 0 … 90
  float reliefM = std::numeric_limits<float>::quiet_NaN();     // height − mean height of the ring
};

// −Σ ((outside distance) / soft)² of `site` against `niche` (≤ 0; 0 inside or unknown).
float logNicheFit(const TreeNiche& niche, const TreeSite& site);

// Stage 2 above at a point where stage 1 chose tree species `first`, z uniform in [0, 1): `first`
// against the tree species that claim no ground, those `allowed` (landcover_species.h). species −1
// when none passes its threshold there (keep `first` then).
// `colour`: the calibrated ground colour there (colour_calibration.h; exg kNoExg: no ExG term).
SpeciesChoice chooseTreeSpecies(const SpeciesCatalog& catalog, int first, const GroundColour& colour, float ndvi,
                                const TreeSite& site, float z, SpeciesMask allowed = kAllSpecies);

}  // namespace vegstream::vegetation
