// The species catalog's JSON (species_catalog.h has the format), core seed
// ../shared/seeds/001_3eca9f2c7752e4fb.txt §3.3 (eq. 16 parameters, thresholds, bare soil).
// Parsing records the first problem with its field path and stops there, so a user sees one
// message naming the file and the field, never an exception (species_json_parser.h); each
// entry of "species" is read by species_entry_parse.cpp, what concerns them together here.
#include "vegetation/species_catalog.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/json_text.h"
#include "core/text_file.h"
#include "vegetation/landcover_table_json.h"
#include "vegetation/species_entry_parse.h"
#include "vegetation/species_json_parser.h"

namespace vegstream::vegetation {
namespace {
using nlohmann::json;
using species_json::fmt;
using species_json::Parser;
using species_json::parseSpecies;

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
