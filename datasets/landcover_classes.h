#pragma once
// Landcover class codes as the sources store them (issue 40, item 4): the class tables of the
// schemes vegstream knows, each class mapped to the coarse kind of ground the species choice
// uses, the scheme of a raster found from the codes it holds, and the codes a scheme does not
// know.
//
// Schemes (the codes are the products' own, so a landcover tile holds what the source holds):
//   worldcover  ESA WorldCover 2020 (v100) and 2021 (v200), 10 m: 10 Tree cover, 20 Shrubland,
//               30 Grassland, 40 Cropland, 50 Built-up, 60 Bare / sparse vegetation, 70 Snow and
//               ice, 80 Permanent water bodies, 90 Herbaceous wetland, 95 Mangroves, 100 Moss
//               and lichen.
//   nlcd        USGS National Land Cover Database (2001 … 2021), 30 m: 11 Open Water, 12
//               Perennial Ice/Snow, 21–24 Developed (open space, low, medium, high intensity),
//               31 Barren Land, 41–43 Deciduous / Evergreen / Mixed Forest, 51 Dwarf Scrub, 52
//               Shrub/Scrub, 71 Grassland/Herbaceous, 72 Sedge/Herbaceous, 73 Lichens, 74 Moss,
//               81 Pasture/Hay, 82 Cultivated Crops, 90 Woody Wetlands, 95 Emergent Herbaceous
//               Wetlands.
// Code 0 is "no data" in the landcover layer whatever the scheme (no class of either uses it).
//
// Kinds, where a class is not plain (judgement calls, in one place):
//   - WorldCover 95 Mangroves and NLCD 90 Woody Wetlands are `tree` (forest that stands in
//     water); `wetland` is herbaceous wetland (WorldCover 90, NLCD 95).
//   - WorldCover 100 Moss and lichen and NLCD 73 Lichens / 74 Moss are `grass`: low ground
//     cover, which NLCD itself files under "Herbaceous".
//   - NLCD 81 Pasture/Hay is `grass` (perennial grasses, grown like grassland); 82 is `crop`.
//   - NLCD 21 Developed, Open Space (lawns, parks; < 20 % impervious) is `built`, as NLCD
//     groups it.
//
// Scheme detection (`auto`): codes that only one scheme has decide (90 and 95 are in both).
// Codes of exactly one scheme must be seen; codes of both, or of neither alone, is an error that
// lists what was seen and asks for --landcover-scheme. Codes neither scheme has do not count
// either way: a fill value the source does not declare as nodata (NLCD files often hold 250
// outside the survey) may cover most of a raster, and the unknown-code warning shows them.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/landcover_kind.h"
#include "core/result.h"

namespace vegstream::datasets {

enum class LandcoverScheme { WorldCover, Nlcd };
using ::vegstream::LandcoverKind;  // core/landcover_kind.h: vegetation/ uses the kinds too

struct LandcoverClass {
  uint8_t code = 0;
  const char* name = "";  // the product's own name, e.g. "Tree cover", "Deciduous Forest"
  LandcoverKind kind = LandcoverKind::Bare;
};

const char* toString(LandcoverScheme s);  // "worldcover", "nlcd" (dataset.json's landcover.scheme)
const char* toString(LandcoverKind k);  // "tree", "shrub", "grass", "crop", "bare", "built", "water", "snow", "wetland"

// "worldcover" | "nlcd" → that scheme; "auto" → nullopt (detect it from the codes). Anything
// else: InvalidInput "landcover scheme 'x' is not known; expected worldcover, nlcd or auto".
Result<std::optional<LandcoverScheme>> parseLandcoverScheme(const std::string& text);

// The scheme's classes in ascending code order.
std::span<const LandcoverClass> landcoverClasses(LandcoverScheme s);
// The class of `code` in `s`; nullptr when the scheme has no such class (0 included).
const LandcoverClass* findLandcoverClass(LandcoverScheme s, uint8_t code);

// Pixels per class code; [0] counts the pixels without data and is ignored below.
using ClassHistogram = std::array<uint64_t, 256>;

// The scheme the codes belong to (see the header comment). Errors (InvalidInput) name
// `sourceName` and what was seen, and end by suggesting --landcover-scheme worldcover|nlcd.
Result<LandcoverScheme> detectLandcoverScheme(const ClassHistogram& histogram, const std::string& sourceName);

struct UnknownClass {
  uint8_t code = 0;
  uint64_t pixels = 0;
  bool operator==(const UnknownClass&) const = default;
};
// The codes seen (count > 0, code ≠ 0) that `s` has no class for, ascending.
std::vector<UnknownClass> unknownClasses(const ClassHistogram& histogram, LandcoverScheme s);
// One warning line for the importer: "class 7: 1234 pixels, unknown to worldcover; it grows
// nothing", several as "classes 7: 1234 pixels, 8: 5 pixels, unknown to worldcover; they grow
// nothing". Empty when `unknown` is.
std::string unknownClassesWarning(const std::vector<UnknownClass>& unknown, LandcoverScheme s);

}  // namespace vegstream::datasets
