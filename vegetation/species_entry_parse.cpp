// One entry of the species catalog's "species" array (species_catalog.h has the format), core
// seed ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 (eq. 16 parameters, thresholds, bare soil).
// The fields are read in the order of the format, stopping at the first problem.
#include "vegetation/species_entry_parse.h"

#include <algorithm>
#include <iterator>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/json_text.h"
#include "vegetation/blade_shape.h"
#include "vegetation/colour_calibration.h"
#include "vegetation/tree_niche_parse.h"

namespace vegstream::vegetation::species_json {
namespace {

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

// A tree species' "tree" object (format in species_catalog.h); defaults from TreeParams.
bool parseTree(Parser& ps, const json& obj, const std::string& path, TreeParams& out) {
  const std::string p = Parser::join(path, "tree");
  const auto it = obj.find("tree");
  if (it == obj.end()) return ps.fail(p, "is missing (a tree species needs its model: form, density_ha, spacing_m, …)");
  const json& t = *it;
  if (!ps.object(t, p) || !ps.onlyKeys(t, p,
                                       {"form", "density_ha", "spacing_m", "branch_levels", "branches", "twigs",
                                        "branch_angle_deg", "trunk_radius_m", "taper", "leaf_size_m", "leaves_per_twig",
                                        "leaf_colour", "bark_colour", "translucency", "niche", "claims_ground"}))
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
  if (const auto levels = t.find("branch_levels");
      levels != t.end() && levels->is_number() && levels->get<double>() > kMaxBranchLevels)
    return ps.fail(p + ".branch_levels", "more branch levels than the model supports (at most " +
                                             std::to_string(kMaxBranchLevels) + ", got " + fmt(levels->get<double>()) +
                                             ")");
  if (!parseCount(ps, t, "branch_levels", p, out.branchLevels, 2, kMaxBranchLevels) ||
      !parseCount(ps, t, "branches", p, out.branches, 3, 256) || !parseCount(ps, t, "twigs", p, out.twigs, 1, 64) ||
      !parseCount(ps, t, "leaves_per_twig", p, out.leavesPerTwig, 1, 256) ||
      !parseBounded(ps, t, "branch_angle_deg", p, out.branchAngleDeg, 10.0, false, 120.0, "in 10 … 120 degrees") ||
      !parseBounded(ps, t, "trunk_radius_m", p, out.trunkRadiusM, 0.0, true, 5.0, "> 0 and ≤ 5 metres") ||
      !parseBounded(ps, t, "taper", p, out.taper, 0.1, false, 0.8,
                    "in 0.1 … 0.8") ||  // the bending shape fits the beam within 1 % there
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
  for (const auto& [key, linear] :
       {std::pair{"leaf_colour", out.leafColour}, std::pair{"bark_colour", out.barkColour}}) {
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

// The name, the optional about (a string) and bare.
bool parseIdentity(Parser& ps, const json& obj, const std::string& path, Species& out) {
  if (!ps.object(obj, path)) return false;
  if (!ps.onlyKeys(
          obj, path,
          {"name", "about", "reference", "weights", "p", "threshold", "bare", "kind", "height_m", "stiffness",
           "width_m", "colour_modulation", "phototropism", "density_m2", "horizon_m", "shadows", "surface", "tree"}))
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
  return true;
}

// weights: h, s, v ≥ 0 and not all 0; ndvi (which needs reference.ndvi) and exg optional.
bool parseWeights(Parser& ps, const json& obj, const std::string& path, bool ndviGiven, ColourScoreParams& score) {
  const std::string wp = path + ".weights";
  const auto w = obj.find("weights");
  if (w == obj.end()) return ps.fail(wp, "is missing");
  if (!ps.object(*w, wp) || !ps.onlyKeys(*w, wp, {"h", "s", "v", "ndvi", "exg"})) return false;
  glm::vec3& wt = score.weights;
  if (!ps.number(*w, "h", wp, wt.x) || !ps.number(*w, "s", wp, wt.y) || !ps.number(*w, "v", wp, wt.z) ||
      !ps.number(*w, "ndvi", wp, score.ndviWeight, false) || !ps.number(*w, "exg", wp, score.exgWeight, false))
    return false;
  for (const auto& [k, v] : {std::pair{"h", wt.x}, std::pair{"s", wt.y}, std::pair{"v", wt.z},
                             std::pair{"ndvi", score.ndviWeight}, std::pair{"exg", score.exgWeight}})
    if (v < 0.0f) return ps.fail(wp + "." + k, "must be ≥ 0 (got " + fmt(v) + ")");
  if (score.ndviWeight > 0.0f && !ndviGiven)
    return ps.fail(path + ".reference.ndvi", "is missing: weights.ndvi is " + fmt(score.ndviWeight) +
                                                 ", so the species needs the NDVI it grows on");
  if (wt.x == 0.0f && wt.y == 0.0f && wt.z == 0.0f)
    return ps.fail(wp, "must not all be 0 (the score would ignore the colour)");
  return true;
}

// The colour score (eq. 16: reference, weights, p), the threshold and the phototropism.
bool parseScore(Parser& ps, const json& obj, const std::string& path, Species& out) {
  bool ndviGiven = false;
  if (!parseReference(ps, obj, path, out.score.reference, out.score.ndviReference, ndviGiven)) return false;
  if (!parseReferenceExg(ps, obj, path, out.score)) return false;
  if (!parseWeights(ps, obj, path, ndviGiven, out.score)) return false;
  if (!ps.number(obj, "p", path, out.score.p)) return false;
  if (!(out.score.p > 0.0f) || out.score.p > 64.0f)
    return ps.fail(path + ".p", "must be > 0 and ≤ 64 (got " + fmt(out.score.p) + ")");
  if (!ps.number(obj, "threshold", path, out.threshold, false)) return false;
  if (out.threshold < 0.0f) return ps.fail(path + ".threshold", "must be ≥ 0 (got " + fmt(out.threshold) + ")");
  if (!ps.number(obj, "phototropism", path, out.phototropism, false)) return false;
  if (!(out.phototropism >= 0.0f && out.phototropism <= 1.0f))
    return ps.fail(path + ".phototropism", "must be in 0 … 1 (got " + fmt(out.phototropism) + ")");
  return true;
}

// The kind and the plant's ranges, required unless bare; the surface (defaulting from the
// kind) and the shadows.
bool parsePlantShape(Parser& ps, const json& obj, const std::string& path, Species& out) {
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
  out.surface = out.bare                                                             ? DetailSurface::Rock
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
  return true;
}

// The density (a tree's from its "tree" object) and the horizon.
bool parseDensity(Parser& ps, const json& obj, const std::string& path, Species& out) {
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
  return true;
}

// Blades (grass, flower stems) take their shape from the stiffness: too soft, and the tip ends
// below the root (blade_shape.h "Units"). Gravel and trees do not bend.
bool checkBladeStiffness(Parser& ps, const std::string& path, const Species& out) {
  const bool need = !out.bare;
  const bool blade = out.kind == RendererKind::Grass || out.kind == RendererKind::Flowers;
  // The softest plant: the minimum at s′ = 0 (kSPrimeStiffnessLo).
  const double least = minimumRelativeStiffness() / kSPrimeStiffnessLo;
  if (need && blade && out.stiffness.min < least)
    return ps.fail(path + ".stiffness.min", "relative to the buckling stiffness k_c, " + fmt(out.stiffness.min) +
                                                " bends the blade's tip below its root (at least " + fmt(least) +
                                                ": a minority plant is " + fmt(kSPrimeStiffnessLo) + " × as stiff)");
  return true;
}

}  // namespace

bool parseSpecies(Parser& ps, const json& obj, const std::string& path, Species& out) {
  return parseIdentity(ps, obj, path, out) && parseScore(ps, obj, path, out) && parsePlantShape(ps, obj, path, out) &&
         parseDensity(ps, obj, path, out) && checkBladeStiffness(ps, path, out);
}

}  // namespace vegstream::vegetation::species_json
