// Landcover class tables, scheme detection and the unknown-code report (landcover_classes.h).

#include "datasets/landcover_classes.h"

#include <algorithm>
#include <array>

#include "datasets/message.h"

namespace vegstream::datasets {
namespace {

using K = LandcoverKind;

// ESA WorldCover 2020 v100 / 2021 v200 product user manuals, the Map code table.
constexpr std::array<LandcoverClass, 11> kWorldCover{{
    {10, "Tree cover", K::Tree},
    {20, "Shrubland", K::Shrub},
    {30, "Grassland", K::Grass},
    {40, "Cropland", K::Crop},
    {50, "Built-up", K::Built},
    {60, "Bare / sparse vegetation", K::Bare},
    {70, "Snow and ice", K::Snow},
    {80, "Permanent water bodies", K::Water},
    {90, "Herbaceous wetland", K::Wetland},
    {95, "Mangroves", K::Tree},
    {100, "Moss and lichen", K::Grass},
}};

// NLCD class legend (MRLC); 51, 72, 73, 74 occur in Alaska only.
constexpr std::array<LandcoverClass, 20> kNlcd{{
    {11, "Open Water", K::Water},
    {12, "Perennial Ice/Snow", K::Snow},
    {21, "Developed, Open Space", K::Built},
    {22, "Developed, Low Intensity", K::Built},
    {23, "Developed, Medium Intensity", K::Built},
    {24, "Developed, High Intensity", K::Built},
    {31, "Barren Land", K::Bare},
    {41, "Deciduous Forest", K::Tree},
    {42, "Evergreen Forest", K::Tree},
    {43, "Mixed Forest", K::Tree},
    {51, "Dwarf Scrub", K::Shrub},
    {52, "Shrub/Scrub", K::Shrub},
    {71, "Grassland/Herbaceous", K::Grass},
    {72, "Sedge/Herbaceous", K::Grass},
    {73, "Lichens", K::Grass},
    {74, "Moss", K::Grass},
    {81, "Pasture/Hay", K::Grass},
    {82, "Cultivated Crops", K::Crop},
    {90, "Woody Wetlands", K::Tree},
    {95, "Emergent Herbaceous Wetlands", K::Wetland},
}};

constexpr std::array<LandcoverScheme, 2> kSchemes{LandcoverScheme::WorldCover, LandcoverScheme::Nlcd};

LandcoverScheme other(LandcoverScheme s) {
  return s == LandcoverScheme::WorldCover ? LandcoverScheme::Nlcd : LandcoverScheme::WorldCover;
}

// "10 (1234 px), 20 (5 px)" for the codes seen that `s` has and the other scheme has not.
struct OwnCodes {
  uint64_t pixels = 0;
  std::string list;
};
OwnCodes ownCodes(const ClassHistogram& h, LandcoverScheme s) {
  OwnCodes out;
  for (const LandcoverClass& c : landcoverClasses(s)) {
    if (h[c.code] == 0 || findLandcoverClass(other(s), c.code)) continue;
    out.pixels += h[c.code];
    if (!out.list.empty()) out.list += ", ";
    out.list += concat(static_cast<int>(c.code), " (", h[c.code], " px)");
  }
  return out;
}

std::string suggestion() { return "; name it with --landcover-scheme worldcover or --landcover-scheme nlcd"; }

}  // namespace

const char* toString(LandcoverScheme s) { return s == LandcoverScheme::WorldCover ? "worldcover" : "nlcd"; }

const char* toString(LandcoverKind k) {
  switch (k) {
    case K::Tree: return "tree";
    case K::Shrub: return "shrub";
    case K::Grass: return "grass";
    case K::Crop: return "crop";
    case K::Bare: return "bare";
    case K::Built: return "built";
    case K::Water: return "water";
    case K::Snow: return "snow";
    case K::Wetland: return "wetland";
  }
  return "bare";
}

Result<std::optional<LandcoverScheme>> parseLandcoverScheme(const std::string& text) {
  if (text == "auto") return std::optional<LandcoverScheme>{};
  for (LandcoverScheme s : kSchemes)
    if (text == toString(s)) return std::optional<LandcoverScheme>(s);
  return makeError(ErrorKind::InvalidInput,
                   concat("landcover scheme '", text, "' is not known; expected worldcover, nlcd or auto"));
}

std::span<const LandcoverClass> landcoverClasses(LandcoverScheme s) {
  if (s == LandcoverScheme::WorldCover) return kWorldCover;
  return kNlcd;
}

const LandcoverClass* findLandcoverClass(LandcoverScheme s, uint8_t code) {
  const auto classes = landcoverClasses(s);
  const auto it = std::lower_bound(classes.begin(), classes.end(), code,
                                   [](const LandcoverClass& c, uint8_t v) { return c.code < v; });
  return it != classes.end() && it->code == code ? &*it : nullptr;
}

Result<LandcoverScheme> detectLandcoverScheme(const ClassHistogram& h, const std::string& sourceName) {
  const OwnCodes wc = ownCodes(h, LandcoverScheme::WorldCover), nlcd = ownCodes(h, LandcoverScheme::Nlcd);
  uint64_t valid = 0;
  for (size_t code = 1; code < h.size(); ++code) valid += h[code];
  const std::string head = concat("cannot tell the landcover scheme of '", sourceName, "': ");
  if (wc.pixels > 0 && nlcd.pixels > 0)
    return makeError(ErrorKind::InvalidInput, concat(head, "it holds codes only WorldCover has, ", wc.list,
                                                     ", and codes only NLCD has, ", nlcd.list, suggestion()));
  if (wc.pixels == 0 && nlcd.pixels == 0) {
    const char* what =
        valid == 0 ? "it holds no class codes at all" : "none of its codes is WorldCover's or NLCD's alone";
    return makeError(ErrorKind::InvalidInput, concat(head, what, suggestion()));
  }
  return wc.pixels > 0 ? LandcoverScheme::WorldCover : LandcoverScheme::Nlcd;
}

std::vector<UnknownClass> unknownClasses(const ClassHistogram& h, LandcoverScheme s) {
  std::vector<UnknownClass> out;
  for (size_t code = 1; code < h.size(); ++code)
    if (h[code] > 0 && !findLandcoverClass(s, static_cast<uint8_t>(code)))
      out.push_back({static_cast<uint8_t>(code), h[code]});
  return out;
}

std::string unknownClassesWarning(const std::vector<UnknownClass>& unknown, LandcoverScheme s) {
  if (unknown.empty()) return {};
  std::string m = unknown.size() == 1 ? "class " : "classes ";
  for (size_t i = 0; i < unknown.size(); ++i) {
    if (i) m += ", ";
    m += concat(static_cast<int>(unknown[i].code), ": ", unknown[i].pixels, " pixels");
  }
  m += concat(", unknown to ", toString(s), unknown.size() == 1 ? "; it grows nothing" : "; they grow nothing");
  return m;
}

}  // namespace vegstream::datasets
