#pragma once
// Which species each landcover kind allows (issue 41, item 2: "landcover classes when the user
// has them"). Where a dataset has a landcover layer, a plant's or tree's species is chosen as
// before (core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 eq. 16–18: the colour score,
// NDVI where there is some) but only among the species the class under it allows
// (species_choice.h's `allowed` mask): the class says *what* may grow, the colour *which* of it.
//
// The catalog's optional "landcover" object (species_catalog.h) gives the allowed species per
// kind by name:
//   "landcover": { "tree": ["conifer", "broadleaf", "grey rock"], "built": [], … }
// keys are the kinds (core/landcover_kind.h: tree, shrub, grass, crop, bare, built, water, snow,
// wetland), each an array of species names of the catalog (bare soil entries included: they take
// part in the choice and grow nothing). A kind the table leaves out keeps the built-in default;
// an empty array grows nothing there. A name the catalog does not have is refused, naming the
// field ("species.json: landcover.tree[1]: no species named \"oak\"").
//
// The built-in default, from the species' kinds (a catalog without the table):
//   tree              the tree species and bare soil        (tree cover grows trees, not meadow)
//   grass, crop,      grass and flowers, and bare soil       (crops are drawn as grass blades;
//   wetland                                                    herbaceous wetland is grass-like)
//   shrub             grass, flowers, gravel and bare soil   (no shrub renderer: low cover; < 10 %
//                                                              tree cover by the classes' own
//                                                              definitions, so no trees)
//   bare              gravel and bare soil                   (stones, nothing that lives)
//   built, water,     nothing
//   snow
// Where it applies: the trees (tree_placement.h, through scene/tree_ground.h: `vegstream plants`
// and a flight's tree field), the plants of `vegstream plants` (scene/plants_in_box.cpp) and
// `vegstream query`. Not yet: the GPU classify pass of a flight's plants (it has the GLSL twin,
// shaders/common/species_choice.glsl chooseSpeciesAllowed, but no landcover texels yet), so a
// flight over a landcover dataset still grows its grass and gravel from the colour alone.
//
// Bare soil stays in every growing kind so that the colour can still say "nothing here" (a rock
// outcrop inside a grassland class).

#include <array>
#include <cstdint>
#include <vector>

#include "core/landcover_kind.h"

namespace vegstream::vegetation {

struct Species;
struct SpeciesCatalog;

// Bit i: catalog species i may be chosen (species_choice.h's `allowed`). kMaxSpecies ≤ 32.
using SpeciesMask = uint32_t;
inline constexpr SpeciesMask kAllSpecies = 0xffffffffu;

using LandcoverTable = std::array<SpeciesMask, kLandcoverKindCount>;

// The built-in default above for these species.
LandcoverTable defaultLandcoverTable(const std::vector<Species>& species);

// The species `kind` allows in `catalog`: its table's entry, else the default's.
SpeciesMask allowedSpecies(const SpeciesCatalog& catalog, LandcoverKind kind);

}  // namespace vegstream::vegetation
