// The species catalog's JSON (species_catalog.h has the format), core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 (eq. 16 parameters, thresholds, bare soil).
// Parsing records the first problem with its field path and stops there, so a user sees one
// message naming the file and the field, never an exception.
#include "vegetation/species_catalog.h"
#include "vegetation/tree_niche_parse.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/json_text.h"
#include "core/text_file.h"
#include "vegetation/blade_shape.h"
#include "vegetation/colour_calibration.h"
#include "vegetation/landcover_table_json.h"

namespace vegstream::vegetation {
namespace {
using nlohmann::json;

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

class Parser {
 public:
  explicit Parser(std::string source) : source_(std::move(source)) {}

  bool fail(const std::string& path, const std::string& problem) {
    // The path holds keys from the file: escaped and bounded like any value from data.
    if (!error_) error_ = makeError(ErrorKind::InvalidInput, source_ + ": " + printable(path, 200) + ": " + problem);
    return false;
  }
  const Error& error() const { return *error_; }
  // fail() as a value to return.
  Error failed(const std::string& path, const std::string& problem) {
    fail(path, problem);
    return *error_;
  }

  bool onlyKeys(const json& obj, const std::string& path, std::initializer_list<std::string_view> allowed) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool known = false;
      for (std::string_view a : allowed) known = known || it.key() == a;
      if (!known) {
        std::string list;
        for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        return fail(join(path, it.key()), "unknown key (allowed here: " + list + ")");
      }
    }
    return true;
  }

  bool object(const json& v, const std::string& path) { return v.is_object() || fail(path, "must be an object"); }

  // A number in [lo, hi] (closed; open bounds are checked by the caller's message).
  bool number(const json& obj, std::string_view key, const std::string& path, float& out, bool required = true) {
    const auto it = obj.find(key);
    if (it == obj.end()) return !required || fail(join(path, key), "is missing");
    if (!it->is_number()) return fail(join(path, key), "must be a number");
    const double d = it->get<double>();
    if (!std::isfinite(d) || std::abs(d) > 1e30) return fail(join(path, key), "must be a finite number");
    out = static_cast<float>(d);
    return true;
  }

  bool range(const json& obj, std::string_view key, const std::string& path, FloatRange& out, double lo, bool loOpen,
             double hi, const char* what) {
    const std::string p = join(path, key);
    const auto it = obj.find(key);
    if (it == obj.end()) return fail(p, "is missing");
    if (!object(*it, p) || !onlyKeys(*it, p, {"min", "max"})) return false;
    if (!number(*it, "min", p, out.min) || !number(*it, "max", p, out.max)) return false;
    for (const auto& [name, v] : {std::pair{"min", out.min}, std::pair{"max", out.max}}) {
      const bool low = loOpen ? !(v > lo) : !(v >= lo);
      if (low || v > hi) return fail(p + "." + name, std::string("must be ") + what + " (got " + fmt(v) + ")");
    }
    if (out.min > out.max) return fail(p + ".max", "must be ≥ min (got " + fmt(out.max) + " < " + fmt(out.min) + ")");
    return true;
  }

  static std::string join(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
  }

 private:
  std::string source_;
  std::optional<Error> error_;
};

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// "#rrggbb" → its three bytes; false when it is not one.
bool parseHexColour(const json& v, int (&rgb)[3]) {
  const std::string text = v.is_string() ? v.get<std::string>() : "";
  if (text.size() != 7 || text[0] != '#') return false;
  for (size_t i = 0; i < 3; ++i) {
    const int hi = hexDigit(text[1 + 2 * i]), lo = hexDigit(text[2 + 2 * i]);
    if (hi < 0 || lo < 0) return false;
    rgb[i] = hi * 16 + lo;
  }
  return true;
}

// reference.ndvi: optional, −1 … 1 (the NDVI channel of the score, colour_score.h).
bool parseReferenceNdvi(Parser& ps, const json& r, const std::string& p, float& ndvi, bool& given) {
  given = r.contains("ndvi");
  if (!ps.number(r, "ndvi", p, ndvi, false)) return false;
  if (ndvi < -1.0f || ndvi > 1.0f) return ps.fail(p + ".ndvi", "must be in −1 … 1 (got " + fmt(ndvi) + ")");
  return true;
}

bool parseReference(Parser& ps, const json& obj, const std::string& path, glm::vec3& hsv, float& ndvi,
                    bool& ndviGiven) {
  const std::string p = Parser::join(path, "reference");
  const auto it = obj.find("reference");
  if (it == obj.end()) return ps.fail(p, "is missing");
  if (!ps.object(*it, p)) return false;
  const json& r = *it;
  if (r.contains("srgb")) {
    if (!ps.onlyKeys(r, p, {"srgb", "ndvi", "exg"})) return ps.fail(p, "give either srgb or h_deg, s, v");
    if (!parseReferenceNdvi(ps, r, p, ndvi, ndviGiven)) return false;
    int v[3] = {};
    if (!parseHexColour(r["srgb"], v)) return ps.fail(p + ".srgb", "must be a colour \"#rrggbb\"");
    hsv = hsvFromSrgb8(static_cast<uint8_t>(v[0]), static_cast<uint8_t>(v[1]), static_cast<uint8_t>(v[2]));
    return true;
  }
  if (!ps.onlyKeys(r, p, {"h_deg", "s", "v", "srgb", "ndvi", "exg"})) return false;
  if (!parseReferenceNdvi(ps, r, p, ndvi, ndviGiven)) return false;
  float h = 0.0f;
  if (!ps.number(r, "h_deg", p, h) || !ps.number(r, "s", p, hsv.y) || !ps.number(r, "v", p, hsv.z)) return false;
  if (h < 0.0f || h > 360.0f) return ps.fail(p + ".h_deg", "must be in 0 … 360 (got " + fmt(h) + ")");
  if (hsv.y < 0.0f || hsv.y > 1.0f) return ps.fail(p + ".s", "must be in 0 … 1 (got " + fmt(hsv.y) + ")");
  if (hsv.z < 0.0f || hsv.z > 1.0f) return ps.fail(p + ".v", "must be in 0 … 1 (got " + fmt(hsv.z) + ")");
  hsv.x = h / 360.0f;
  if (hsv.x >= 1.0f) hsv.x -= 1.0f;  // 360° is 0°: hues live in [0, 1) like hsvFromSrgb's
  return true;
}

// reference.exg: optional, −1 … 2; by default the excess green of the reference colour itself
// (colour_calibration.h), so a catalog gets the index term by giving only weights.exg.
bool parseReferenceExg(Parser& ps, const json& obj, const std::string& path, ColourScoreParams& score) {
  const glm::vec3 srgb = srgbFromHsv(score.reference);
  score.exgReference = excessGreen({srgbDecode(srgb.r), srgbDecode(srgb.g), srgbDecode(srgb.b)});
  const std::string p = Parser::join(path, "reference");
  const json& r = obj["reference"];
  if (!ps.number(r, "exg", p, score.exgReference, false)) return false;
  if (score.exgReference < -1.0f || score.exgReference > 2.0f)
    return ps.fail(p + ".exg", "must be in −1 … 2 (got " + fmt(score.exgReference) + ")");
  return true;
}

// An optional whole number in [lo, hi] (default kept when absent).
bool parseCount(Parser& ps, const json& obj, std::string_view key, const std::string& path, uint32_t& out, uint32_t lo,
                uint32_t hi) {
  const auto it = obj.find(key);
  if (it == obj.end()) return true;
  const std::string p = Parser::join(path, key);
  if (!it->is_number_integer() && !(it->is_number_float() && std::floor(it->get<double>()) == it->get<double>()))
    return ps.fail(p, "must be a whole number");
  const double v = it->get<double>();
  if (v < lo || v > hi)
    return ps.fail(p, "must be " + std::to_string(lo) + " … " + std::to_string(hi) + " (got " + fmt(v) + ")");
  out = static_cast<uint32_t>(v);
  return true;
}

// An optional number in [lo, hi], or (lo, hi] when loOpen (default kept when absent).
bool parseBounded(Parser& ps, const json& obj, std::string_view key, const std::string& path, float& out, double lo,
                  bool loOpen, double hi, const char* what, bool required = false) {
  if (!ps.number(obj, key, path, out, required)) return false;
  if ((loOpen ? !(out > lo) : !(out >= lo)) || out > hi)
    return ps.fail(Parser::join(path, key), std::string("must be ") + what + " (got " + fmt(out) + ")");
  return true;
}

// A tree species' "tree" object (format in species_catalog.h); defaults from TreeParams.
bool parseTree(Parser& ps, const json& obj, const std::string& path, TreeParams& out) {
  const std::string p = Parser::join(path, "tree");
  const auto it = obj.find("tree");
  if (it == obj.end()) return ps.fail(p, "is missing (a tree species needs its model: form, density_ha, spacing_m, …)");
  const json& t = *it;
  if (!ps.object(t, p) ||
      !ps.onlyKeys(t, p,
                   {"form", "density_ha", "spacing_m", "branch_levels", "branches", "twigs", "branch_angle_deg",
                    "trunk_radius_m", "taper", "leaf_size_m", "leaves_per_twig", "leaf_colour", "bark_colour",
                    "translucency", "niche", "claims_ground"}))
    return false;
  const auto form = t.find("form");
  if (form == t.end()) return ps.fail(p + ".form", "is missing (\"conifer\" or \"broadleaf\")");
  const std::string f = form->is_string() ? form->get<std::string>() : "";
  if (f == "conifer")
    out.form = TreeForm::Conifer;
  else if (f == "broadleaf")
    out.form = TreeForm::Broadleaf;
  else
    return ps.fail(p + ".form", "must be \"conifer\" or \"broadleaf\" (got " + jsonValueText(*form) + ")");
  if (!parseBounded(ps, t, "density_ha", p, out.densityHa, 0.0, true, 10000.0, "> 0 and ≤ 10000 trees per hectare",
                    true) ||
      !parseBounded(ps, t, "spacing_m", p, out.spacingM, 0.0, true, 100.0, "> 0 and ≤ 100 metres", true))
    return false;
  // branch_levels: its own message above the maximum, the limit being the model's, not taste.
  if (const auto levels = t.find("branch_levels"); levels != t.end() && levels->is_number() &&
                                                    levels->get<double>() > kMaxBranchLevels)
    return ps.fail(p + ".branch_levels", "more branch levels than the model supports (at most " +
                                             std::to_string(kMaxBranchLevels) + ", got " + fmt(levels->get<double>()) +
                                             ")");
  if (!parseCount(ps, t, "branch_levels", p, out.branchLevels, 2, kMaxBranchLevels) ||
      !parseCount(ps, t, "branches", p, out.branches, 3, 256) || !parseCount(ps, t, "twigs", p, out.twigs, 1, 64) ||
      !parseCount(ps, t, "leaves_per_twig", p, out.leavesPerTwig, 1, 256) ||
      !parseBounded(ps, t, "branch_angle_deg", p, out.branchAngleDeg, 10.0, false, 120.0, "in 10 … 120 degrees") ||
      !parseBounded(ps, t, "trunk_radius_m", p, out.trunkRadiusM, 0.0, true, 5.0, "> 0 and ≤ 5 metres") ||
      !parseBounded(ps, t, "taper", p, out.taper, 0.1, false, 0.8, "in 0.1 … 0.8") ||  // the bending shape fits the beam within 1 % there
      !parseBounded(ps, t, "leaf_size_m", p, out.leafSizeM, 0.0, true, 5.0, "> 0 and ≤ 5 metres") ||
      !parseBounded(ps, t, "translucency", p, out.translucency, 0.0, false, 1.0, "in 0 … 1"))
    return false;
  if (const auto claims = t.find("claims_ground"); claims != t.end()) {
    if (!claims->is_boolean()) return ps.fail(p + ".claims_ground", "must be true or false");
    out.claimsGround = claims->get<bool>();
  }
  if (const auto niche = t.find("niche"); niche != t.end()) {
    std::string field, problem;
    if (!parseTreeNiche(*niche, out.niche, field, problem)) return ps.fail(p + ".niche" + field, problem);
  }
  for (const auto& [key, linear] : {std::pair{"leaf_colour", out.leafColour}, std::pair{"bark_colour", out.barkColour}}) {
    const auto c = t.find(key);
    if (c == t.end()) continue;
    int rgb[3] = {};
    if (!parseHexColour(*c, rgb)) return ps.fail(p + "." + key, "must be a colour \"#rrggbb\" (sRGB)");
    for (int i = 0; i < 3; ++i) linear[i] = srgbDecode(static_cast<float>(rgb[i]) / 255.0f);
  }
  return true;
}

bool parseKind(Parser& ps, const json& obj, const std::string& path, RendererKind& kind) {
  const std::string p = Parser::join(path, "kind");
  const auto it = obj.find("kind");
  if (it == obj.end()) return ps.fail(p, "is missing (grass, gravel, flowers or tree; or \"bare\": true)");
  const std::string k = it->is_string() ? it->get<std::string>() : "";
  for (RendererKind c : {RendererKind::Grass, RendererKind::Gravel, RendererKind::Flowers, RendererKind::Tree})
    if (k == rendererKindName(c)) {
      kind = c;
      return true;
    }
  return ps.fail(p, "must be \"grass\", \"gravel\", \"flowers\" or \"tree\" (got " + jsonValueText(*it) + ")");
}

bool parseSpecies(Parser& ps, const json& obj, const std::string& path, Species& out) {
  if (!ps.object(obj, path)) return false;
  if (!ps.onlyKeys(obj, path,
                   {"name", "about", "reference", "weights", "p", "threshold", "bare", "kind", "height_m", "stiffness",
                    "width_m", "colour_modulation", "phototropism", "density_m2", "horizon_m", "shadows", "surface",
                    "tree"}))
    return false;
  const auto name = obj.find("name");
  if (name == obj.end()) return ps.fail(path + ".name", "is missing");
  if (!name->is_string() || name->get<std::string>().empty())
    return ps.fail(path + ".name", "must be a non-empty string");
  out.name = name->get<std::string>();
  if (const auto about = obj.find("about"); about != obj.end() && !about->is_string())
    return ps.fail(path + ".about", "must be a string");
  if (const auto bare = obj.find("bare"); bare != obj.end()) {
    if (!bare->is_boolean()) return ps.fail(path + ".bare", "must be true or false");
    out.bare = bare->get<bool>();
  }

  bool ndviGiven = false;
  if (!parseReference(ps, obj, path, out.score.reference, out.score.ndviReference, ndviGiven)) return false;
  if (!parseReferenceExg(ps, obj, path, out.score)) return false;
  const std::string wp = path + ".weights";
  const auto w = obj.find("weights");
  if (w == obj.end()) return ps.fail(wp, "is missing");
  if (!ps.object(*w, wp) || !ps.onlyKeys(*w, wp, {"h", "s", "v", "ndvi", "exg"})) return false;
  glm::vec3& wt = out.score.weights;
  if (!ps.number(*w, "h", wp, wt.x) || !ps.number(*w, "s", wp, wt.y) || !ps.number(*w, "v", wp, wt.z) ||
      !ps.number(*w, "ndvi", wp, out.score.ndviWeight, false) || !ps.number(*w, "exg", wp, out.score.exgWeight, false))
    return false;
  for (const auto& [k, v] : {std::pair{"h", wt.x}, std::pair{"s", wt.y}, std::pair{"v", wt.z},
                             std::pair{"ndvi", out.score.ndviWeight}, std::pair{"exg", out.score.exgWeight}})
    if (v < 0.0f) return ps.fail(wp + "." + k, "must be ≥ 0 (got " + fmt(v) + ")");
  if (out.score.ndviWeight > 0.0f && !ndviGiven)
    return ps.fail(path + ".reference.ndvi", "is missing: weights.ndvi is " + fmt(out.score.ndviWeight) +
                                                 ", so the species needs the NDVI it grows on");
  if (wt.x == 0.0f && wt.y == 0.0f && wt.z == 0.0f)
    return ps.fail(wp, "must not all be 0 (the score would ignore the colour)");
  if (!ps.number(obj, "p", path, out.score.p)) return false;
  if (!(out.score.p > 0.0f) || out.score.p > 64.0f)
    return ps.fail(path + ".p", "must be > 0 and ≤ 64 (got " + fmt(out.score.p) + ")");
  if (!ps.number(obj, "threshold", path, out.threshold, false)) return false;
  if (out.threshold < 0.0f) return ps.fail(path + ".threshold", "must be ≥ 0 (got " + fmt(out.threshold) + ")");
  if (!ps.number(obj, "phototropism", path, out.phototropism, false)) return false;
  if (!(out.phototropism >= 0.0f && out.phototropism <= 1.0f))
    return ps.fail(path + ".phototropism", "must be in 0 … 1 (got " + fmt(out.phototropism) + ")");

  // Bare soil grows nothing: the plant fields are optional there (checked when given).
  const bool need = !out.bare;
  if (need || obj.contains("kind"))
    if (!parseKind(ps, obj, path, out.kind)) return false;
  const struct {
    const char* key;
    FloatRange* range;
    double lo;
    bool loOpen;
    double hi;
    const char* what;
  } ranges[] = {{"height_m", &out.heightM, 0.0, true, 200.0, "> 0 and ≤ 200"},
                {"stiffness", &out.stiffness, 0.0, true, 1e6, "> 0"},
                {"width_m", &out.widthM, 0.0, true, 50.0, "> 0 and ≤ 50"},
                {"colour_modulation", &out.colourModulation, 0.0, false, 4.0, "in 0 … 4"}};
  for (const auto& r : ranges)
    if (need || obj.contains(r.key))
      if (!ps.range(obj, r.key, path, *r.range, r.lo, r.loOpen, r.hi, r.what)) return false;
  out.surface = out.bare                              ? DetailSurface::Rock
                : out.kind == RendererKind::Tree || out.kind == RendererKind::Gravel ? DetailSurface::Gravel
                                                                                     : DetailSurface::Grass;
  if (const auto sf = obj.find("surface"); sf != obj.end()) {
    static const char* kNames[] = {"grass", "rock", "gravel", "sand"};
    const std::string v = sf->is_string() ? sf->get<std::string>() : "";
    const auto at = std::find(std::begin(kNames), std::end(kNames), v);
    if (at == std::end(kNames))
      return ps.fail(path + ".surface",
                     "must be \"grass\", \"rock\", \"gravel\" or \"sand\" (got " + jsonValueText(*sf) + ")");
    out.surface = static_cast<DetailSurface>(at - std::begin(kNames));
  }
  if (const auto sh = obj.find("shadows"); sh != obj.end()) {
    if (!sh->is_boolean()) return ps.fail(path + ".shadows", "must be true or false");
    out.shadows = sh->get<bool>();
  }
  if (isTree(out)) {
    // Trees have their own density (per hectare, on their own grid) and a horizon of kilometres.
    if (obj.contains("density_m2"))
      return ps.fail(path + ".density_m2", "not for trees (give tree.density_ha, trees per hectare)");
    if (!parseTree(ps, obj, path, out.tree)) return false;
    out.densityM2 = out.tree.densityHa / 10000.0f;
    out.horizonM = kDefaultTreeHorizonM;
  } else {
    if (obj.contains("tree")) return ps.fail(path + ".tree", "only for species of kind \"tree\"");
    if (!ps.number(obj, "density_m2", path, out.densityM2, false)) return false;
    if (!(out.densityM2 > 0.0f && out.densityM2 <= 10000.0f))
      return ps.fail(path + ".density_m2", "must be > 0 and ≤ 10000 plants per m² (got " + fmt(out.densityM2) + ")");
  }
  if (!ps.number(obj, "horizon_m", path, out.horizonM, false)) return false;
  if (!(out.horizonM > 0.0f && out.horizonM <= 20000.0f))
    return ps.fail(path + ".horizon_m", "must be > 0 and ≤ 20000 metres (got " + fmt(out.horizonM) + ")");
  // Blades (grass, flower stems) take their shape from the stiffness: too soft, and the tip ends
  // below the root (blade_shape.h "Units"). Gravel and trees do not bend.
  const bool blade = out.kind == RendererKind::Grass || out.kind == RendererKind::Flowers;
  // The softest plant: the minimum at s′ = 0 (kSPrimeStiffnessLo).
  const double least = minimumRelativeStiffness() / kSPrimeStiffnessLo;
  if (need && blade && out.stiffness.min < least)
    return ps.fail(path + ".stiffness.min", "relative to the buckling stiffness k_c, " + fmt(out.stiffness.min) +
                                                " bends the blade's tip below its root (at least " + fmt(least) +
                                                ": a minority plant is " + fmt(kSPrimeStiffnessLo) + " × as stiff)");
  return true;
}

// nlohmann's message without its "[json.exception.parse_error.101] " tag.
std::string jsonProblem(const json::exception& e) { return jsonExceptionText(e.what()); }

// What concerns the tree species together: each tree horizon reaches at least as far as every
// other growing species' (issue 20: the forest outlasts the meadow), and each spacing fits the
// placement grid the densest tree species sets (tree_placement.h: cell = 100 √(0.9 / D) m, the
// margin between trees the largest spacing, at most 0.7 cell).
Status checkTrees(Parser& ps, const SpeciesCatalog& catalog) {
  const Species* farthestPlant = nullptr;
  const Species* densest = nullptr;
  for (const Species& s : catalog.species) {
    if (s.bare) continue;
    if (!isTree(s) && (!farthestPlant || s.horizonM > farthestPlant->horizonM)) farthestPlant = &s;
    if (isTree(s) && (!densest || s.tree.densityHa > densest->tree.densityHa)) densest = &s;
  }
  for (size_t i = 0; i < catalog.species.size(); ++i) {
    const Species& s = catalog.species[i];
    if (!isTree(s)) continue;
    const std::string path = "species[" + std::to_string(i) + "]";
    if (farthestPlant && s.horizonM < farthestPlant->horizonM)
      return ps.failed(path + ".horizon_m", "a tree horizon shorter than the " + farthestPlant->name + "'s (" +
                                                fmt(farthestPlant->horizonM) + " m): got " + fmt(s.horizonM) + " m");
    const double d = densest->tree.densityHa;
    const double cellM = 100.0 * std::sqrt(double(kTreeCellShare) / d);
    const double largest = kTreeSpacingPerCell * cellM;
    if (d * std::pow(s.tree.spacingM / kTreeSpacingPerCell, 2.0) > 1e4 * kTreeCellShare)
      return ps.failed(path + ".tree.spacing_m",
                       fmt(s.tree.spacingM) + " m does not fit the placement grid of the densest tree species (" +
                           densest->name + ", " + fmt(d) + " trees/ha: cells of " + fmt(cellM) +
                           " m, at most 0.7 of a cell between trees): at most " + fmt(std::floor(largest * 100) / 100) +
                           " m");
  }
  return {};
}

Result<SpeciesCatalog> readCatalog(const json& doc, const std::string& sourceName) {
  Parser ps(sourceName);
  SpeciesCatalog out;
  if (!doc.is_object())
    return makeError(ErrorKind::InvalidInput, sourceName + ": must be a JSON object with \"species\": [...]");
  if (!ps.onlyKeys(doc, "", {"about", "species", "landcover"})) return ps.error();
  if (const auto about = doc.find("about"); about != doc.end() && !about->is_string() && !about->is_object())
    return ps.failed("about", "must be a string or an object of strings (field → what it means)");
  const auto list = doc.find("species");
  if (list == doc.end()) return ps.failed("species", "is missing");
  if (!list->is_array() || list->empty() || list->size() > kMaxSpecies)
    return ps.failed("species", "must be an array of 1 … " + std::to_string(kMaxSpecies) + " species (got " +
                                    (list->is_array() ? std::to_string(list->size()) : list->type_name()) + ")");
  std::set<std::string> names;
  bool anyPlant = false;
  for (size_t i = 0; i < list->size(); ++i) {
    const std::string path = "species[" + std::to_string(i) + "]";
    Species s;
    if (!parseSpecies(ps, (*list)[i], path, s)) return ps.error();
    if (!names.insert(s.name).second) return ps.failed(path + ".name", "duplicate name \"" + s.name + "\"");
    anyPlant = anyPlant || !s.bare;
    out.species.push_back(std::move(s));
  }
  if (!anyPlant) return ps.failed("species", "every entry is bare soil: at least one must grow plants");
  if (Status s = checkTrees(ps, out); !s) return s.error();
  if (const auto lc = doc.find("landcover"); lc != doc.end()) {
    auto table = readLandcoverTable(*lc, out.species, sourceName);
    if (!table) return table.error();
    out.landcover = *table;
  }
  return out;
}

}  // namespace

const char* rendererKindName(RendererKind kind) {
  switch (kind) {
    case RendererKind::Grass: return "grass";
    case RendererKind::Gravel: return "gravel";
    case RendererKind::Flowers: return "flowers";
    case RendererKind::Tree: return "tree";
  }
  return "?";
}

Result<SpeciesCatalog> parseSpeciesCatalog(std::string_view text, const std::string& sourceName) {
  // Caught here, so the caller gets a value, as everywhere: parse_error, and out_of_range for a
  // number no double holds ("1e9999"); the walk checks every type before reading, and the second
  // catch keeps a missed case an error value rather than an abort.
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    return makeError(ErrorKind::InvalidInput, sourceName + ": not valid JSON (" + jsonProblem(e) + ")");
  }
  try {
    return readCatalog(doc, sourceName);
  } catch (const json::exception& e) {
    return makeError(ErrorKind::InvalidInput, sourceName + ": " + jsonProblem(e));
  }
}

float densestGroundDensity(const SpeciesCatalog& catalog) {
  float d = 0.0f;
  for (const Species& s : catalog.species)
    if (!s.bare && !isTree(s)) d = std::max(d, s.densityM2);
  return d;
}

float farthestHorizon(const SpeciesCatalog& catalog) {
  float h = 0.0f;
  for (const Species& s : catalog.species)
    if (!s.bare && !isTree(s)) h = std::max(h, s.horizonM);
  return h;
}

float densestTreeDensityHa(const SpeciesCatalog& catalog) {
  float d = 0.0f;
  for (const Species& s : catalog.species)
    if (isTree(s)) d = std::max(d, s.tree.densityHa);
  return d;
}

float largestTreeSpacing(const SpeciesCatalog& catalog) {
  float m = 0.0f;
  for (const Species& s : catalog.species)
    if (isTree(s)) m = std::max(m, s.tree.spacingM);
  return m;
}

float farthestTreeHorizon(const SpeciesCatalog& catalog) {
  float h = 0.0f;
  for (const Species& s : catalog.species)
    if (isTree(s)) h = std::max(h, s.horizonM);
  return h;
}

bool hasTrees(const SpeciesCatalog& catalog) {
  return std::any_of(catalog.species.begin(), catalog.species.end(), [](const Species& s) { return isTree(s); });
}

Result<SpeciesCatalog> loadSpeciesCatalog(const std::filesystem::path& file) {
  auto text = readTextFile(file, "no such species catalog");
  if (!text) return text.error();
  return parseSpeciesCatalog(*text, file.string());
}

Result<SpeciesCatalog> loadSpeciesCatalogOrDefault(const std::filesystem::path& file) {
  if (file.empty()) return defaultSpeciesCatalog();
  return loadSpeciesCatalog(file);
}

const SpeciesCatalog& defaultSpeciesCatalog() {
  static const SpeciesCatalog catalog = [] {
    auto parsed = parseSpeciesCatalog(defaultSpeciesCatalogJson(), "config/species.json (embedded)");
    assert(parsed.ok() && "the shipped config/species.json must parse (tests/vegetation/species_catalog_test.cpp)");
    return parsed.ok() ? std::move(parsed).value() : SpeciesCatalog{};
  }();
  return catalog;
}

}  // namespace vegstream::vegetation
