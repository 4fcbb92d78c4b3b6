#pragma once
// The species catalog: which plants exist and which imagery colours each one grows on.
// Core seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3: every species has a reference
// colour r, channel weights w and an exponent p for the colour score of eq. 16, an optional
// threshold (a score below it counts as 0, so a species can stay out of colours that merely
// happen to be closer to it than to anything else), and "bare soil" entries that take part in
// the choice but grow nothing (a seed that picks one is rejected).
//
// The catalog is a human-edited JSON file (config/species.json is the default, embedded into
// the program at build time; `--species FILE` replaces it). Its format:
//
//   { "about": "…free text…",
//     "species": [                                         1 … kMaxSpecies entries, ≥ 1 not bare
//       { "name": "grass",                                 unique, non-empty
//         "about": "…free text…",                          optional
//         "reference": { "h_deg": 86, "s": 0.3, "v": 0.33 }   HSV: hue 0 … 360°, s, v in 0 … 1
//                   or { "srgb": "#4a5042" },              8-bit sRGB of an imagery pixel, both
//                                                          of the calibrated colour (colour_calibration.h)
//           optional in either form: "ndvi": 0.4           the NDVI it grows on, −1 … 1
//                                    "exg": 0.3            the excess green, −1 … 2 (default:
//                                                          the reference colour's own)
//         "weights": { "h": 2, "s": 0.8, "v": 0.6 },       ≥ 0, not all 0
//           optional: "ndvi": 2                            ≥ 0 (needs reference.ndvi); counts
//                                                          only where the dataset has NDVI
//                     "exg": 1                             ≥ 0 (default 0): the excess-green term
//         "p": 3,                                          > 0, ≤ 64
//         "threshold": 0,                                  optional, ≥ 0 (0: none)
//         "bare": false,                                   optional
//         "kind": "grass" | "gravel" | "flowers" | "tree", required unless bare
//         "height_m": { "min": 0.15, "max": 0.5 },         > 0, min ≤ max   } required
//         "stiffness": { "min": 0.8, "max": 1.6 },         k′ / k_c > 0     } unless bare
//         "width_m": { "min": 0.004, "max": 0.01 },        > 0              } (checked
//         "colour_modulation": { "min": 0.8, "max": 1.2 }  0 … 4            }  when given)
//         "density_m2": 150,                               optional, > 0, ≤ 10000 (default 10); not for trees
//         "horizon_m": 150,                                optional, > 0, ≤ 20000 (default 150; trees 3000,
//                                                          and a tree's at least every other growing one's)
//         "shadows": true,                                 optional (default true)
//         "surface": "grass" | "rock" | "gravel" | "sand"  optional (default from the kind)
//         "tree": { … }                                    required for kind "tree", else an error:
//       }, … ],
//   "landcover": { "tree": ["conifer", …], … }             optional: the species each landcover
//                                                          kind allows (landcover_species.h)
// }
//
// A tree species' "tree" object (issue 20; TreeParams in tree_types.h; its trees take their height
// from height_m and their crown width from width_m):
//   "form": "conifer" | "broadleaf",      required
//   "density_ha": 180,                    required, > 0, ≤ 10000: trees per hectare where it is chosen
//   "spacing_m": 3.5,                     required, > 0: no two full-width trees closer (smaller crowns
//                                         proportionally closer, tree_placement.h); with the densest tree
//                                         species' density D: D · (spacing / 0.7)² ≤ 9000 (the
//                                         placement grid's cells, tree_placement.h)
//   "branch_levels": 2,                   2 … kMaxBranchLevels (3)               } optional, defaults
//   "branches": 24, "twigs": 6,           3 … 256, 1 … 64                        } from TreeParams
//   "branch_angle_deg": 70,               10 … 120                               }
//   "trunk_radius_m": 0.25,               > 0, ≤ 5 (per 10 m of height)          }
//   "taper": 0.2,                         0.1 … 0.8                              }
//   "leaf_size_m": 0.6,                   > 0, ≤ 5                               }
//   "leaves_per_twig": 8,                 1 … 256                                }
//   "leaf_colour": "#rrggbb", "bark_colour": "#rrggbb"   sRGB, stored linear     }
//   "translucency": 0.5                   0 … 1                                  }
//
// Every key not listed is an error (a typo must not pass silently), and every error names the
// source and the field path: "species.json: species[2].height_m.max: must be ≥ min (got 0.1 < 0.3)".

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"
#include "vegetation/colour_calibration.h"
#include "vegetation/colour_score.h"
#include "vegetation/landcover_species.h"
#include "vegetation/tree_types.h"

namespace vegstream::vegetation {

// How a species is drawn (one tessellation pipeline each, DESIGN.md §3.5). JSON: "grass",
// "gravel", "flowers", "tree". The values are what the GPU sees.
enum class RendererKind : uint32_t { Grass = 0, Gravel = 1, Flowers = 2, Tree = 3 };

// The detail pattern the terrain draws close up where this species' colour is (render/
// detail_textures.h: one texture layer each, in this order). JSON: "grass", "rock", "gravel",
// "sand". The catalog is the one table of ground types (issue 18): the same eq. 16 scores pick
// the species and blend the terrain's detail.
enum class DetailSurface : uint32_t { Grass = 0, Rock = 1, Gravel = 2, Sand = 3 };
inline constexpr uint32_t kDetailSurfaceCount = 4;

const char* rendererKindName(RendererKind kind);

// A closed range [min, max] a per-plant value is drawn from.
struct FloatRange {
  float min = 0.0f, max = 0.0f;
};

struct Species {
  std::string name;
  ColourScoreParams score;                  // reference HSV (hue in [0, 1)), weights, p (eq. 16)
  float threshold = 0.0f;                   // score s below this → s = 0 for this species (0: no threshold)
  bool bare = false;                        // bare soil: seeds that pick it are rejected
  RendererKind kind = RendererKind::Grass;  // ignored when bare
  // 0: blades face every way alike; 1: every blade leans towards the sun (seed 001 §2.3: "a
  // unimodal distribution centered around the direction opposite to the direction of sunlight",
  // against the light's travel: plants grow towards light); between, the orientation spread
  // about that direction shrinks from ±180° to 0.
  float phototropism = 0.0f;
  FloatRange heightM, stiffness, widthM,
      colourModulation;  // per-plant ranges; zero when bare and not given. stiffness is relative
                         // to the buckling stiffness, k′ / k_c (blade_shape.h "Units"): grass and
                         // flowers need min ≥ minimumRelativeStiffness() / kSPrimeStiffnessLo
                         // (≈ 0.75), else a minority plant's tip would end below its root
  // Ground density at full detail, plants per m² of ground where this species is chosen: the
  // most a close camera grows (issue 18). The screen-space ρ of eq. 1 thins it with distance.
  float densityM2 = 10.0f;
  // Plants of this species fade out (shrinking, at the end of their triangle's sequence) over
  // the last quarter of this distance to the camera, metres; gone beyond it.
  float horizonM = 150.0f;
  // Whether its plants cast the planar shadows of §3.6. A meadow's blades cover the ground their
  // shadows would fall on; drawing them doubled the plants pass at eye height (issue 18).
  bool shadows = true;
  // The terrain's detail under it; by default from the kind: grass and flowers grass, trees
  // gravel (a forest floor of litter), gravel gravel, bare soil rock.
  DetailSurface surface = DetailSurface::Grass;
  // Trees only (isTree): the model and placement parameters of the "tree" object. For a tree,
  // densityM2 is tree.densityHa / 10⁴ (trees per m², so a plant pipeline that still counted it
  // would grow next to none) and horizonM its tree horizon (default kDefaultTreeHorizonM).
  TreeParams tree;
};

inline constexpr float kDefaultTreeHorizonM = 3000.0f;
// The placement grid's cells must hold the largest spacing with room to jitter:
// densest tree density · (spacing / kTreeSpacingPerCell)² ≤ kTreeCellShare · 10⁴ m² (tree_placement.h).
inline constexpr double kTreeSpacingPerCell = 0.7, kTreeCellShare = 0.9;

// A species that grows as a tree (not bare, kind tree): placed by tree_placement.h, not by the
// plant seeding.
inline bool isTree(const Species& s) { return !s.bare && s.kind == RendererKind::Tree; }

inline constexpr size_t kMaxSpecies = 16;
static_assert(kMaxSpecies <= 32, "landcover_species.h: one bit a species");

// Eq. 18's s′ modulates a plant's size and stiffness (seed 001 §3.3: "to modulate certain plant
// parameters, such as plant size or stiffness, to give a more natural appearance"): a plant of
// the minority species at a border (s′ → 0) is smaller, thinner and softer than one where its
// species dominates (s′ → 1). Each factor is lo + (1 − lo) s′; shaders/common/plant_params.glsl
// holds the same numbers.
inline constexpr float kSPrimeHeightLo = 0.6f, kSPrimeWidthLo = 0.8f, kSPrimeStiffnessLo = 0.85f;
inline float sPrimeFactor(float lo, float sPrime) { return lo + (1.0f - lo) * sPrime; }

struct SpeciesCatalog {
  std::vector<Species> species;  // 1 … kMaxSpecies, at least one not bare
  // The "landcover" table: per kind, the species it allows (bit i: species i); nullopt: the
  // built-in default (landcover_species.h). Used only where a dataset has a landcover layer.
  std::optional<LandcoverTable> landcover;
  // The dataset's colour calibration (colour_calibration.h): not part of the JSON; whoever opens
  // a dataset sets it (scene/dataset_calibration.h) before choosing species on its imagery, so
  // the GPU pass and every CPU path see the same calibrated colours. Identity by default.
  ColourCalibration calibration;
  // The dataset's landcover class codes → the species each allows (scene/landcover_masks.h), set
  // like `calibration` by whoever opens a dataset with a landcover layer, for the GPU's choice
  // (render/classify_layout.h); nullopt: no layer, every species everywhere. Not part of the JSON.
  std::optional<std::array<SpeciesMask, 256>> landcoverCodes;
};

// The densest species that grows as a plant (not bare, not a tree), plants per m²: how many
// plants a seed triangle's sequence holds at full detail. And the farthest horizon of one, metres.
// Trees are placed on their own grid (tree_placement.h) and count in neither.
float densestGroundDensity(const SpeciesCatalog& catalog);
float farthestHorizon(const SpeciesCatalog& catalog);
// The tree species' own figures: the densest tree.densityHa (trees per ha), the largest
// tree.spacingM (m) and the farthest tree horizon (m); 0 when the catalog has no tree.
float densestTreeDensityHa(const SpeciesCatalog& catalog);
float largestTreeSpacing(const SpeciesCatalog& catalog);
float farthestTreeHorizon(const SpeciesCatalog& catalog);
bool hasTrees(const SpeciesCatalog& catalog);

// `sourceName` names the text in errors (a file name, "embedded default").
Result<SpeciesCatalog> parseSpeciesCatalog(std::string_view json, const std::string& sourceName);
// NotFound when the file is missing; InvalidInput for bad JSON or fields (named).
Result<SpeciesCatalog> loadSpeciesCatalog(const std::filesystem::path& file);

// The catalog a command's --species names, or the default one where it names none (`file`
// empty): loadSpeciesCatalog's errors, else a copy.
Result<SpeciesCatalog> loadSpeciesCatalogOrDefault(const std::filesystem::path& file);

// config/species.json as embedded at build time, parsed once (a bad shipped file is a build
// defect: the tests parse it, and this asserts).
const SpeciesCatalog& defaultSpeciesCatalog();
// The embedded text itself (generated from config/species.json by CMake).
std::string_view defaultSpeciesCatalogJson();

}  // namespace vegstream::vegetation
