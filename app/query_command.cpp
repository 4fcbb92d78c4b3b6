// `vegstream query` (query_command.h).

#include "app/query_command.h"

#include <cmath>
#include <array>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/exit_codes.h"
#include "datasets/dataset_reader.h"
#include "scene/dataset_calibration.h"
#include "scene/landcover_masks.h"
#include "vegetation/colour_score.h"
#include "vegetation/species_choice.h"

namespace vegstream::app {

namespace {

// The species the colour score picks at a base colour and NDVI (core seed §3.3 eq. 16–18, the
// NDVI term of colour_score.h; NaN: none): the best one and the probabilities of the two best,
// deterministic (no z); through the dataset's colour calibration (the catalog's), as plants see it.
// `allowed`: the species the landcover class there allows (scene/landcover_masks.h).
nlohmann::json speciesJson(const vegetation::SpeciesCatalog& catalog, const datasets::Rgb8& c, float ndvi,
                           vegetation::SpeciesMask allowed) {
  const glm::vec3 linear(vegetation::srgbDecode(c[0] / 255.0f), vegetation::srgbDecode(c[1] / 255.0f),
                         vegetation::srgbDecode(c[2] / 255.0f));
  const vegetation::SpeciesCandidates k = speciesCandidatesAt(catalog, linear, ndvi, allowed);
  nlohmann::json out;
  out["excess_green"] = std::round(vegetation::calibratedGround(catalog.calibration, linear).exg * 1e4) / 1e4;
  if (k.first < 0) {  // every species under its threshold
    out["species"] = nullptr;
    out["species_bare"] = true;
    out["canopy_cover"] = 0.0;
    out["species_candidates"] = nlohmann::json::array();
    return out;
  }
  const auto& best = catalog.species[static_cast<size_t>(k.first)];
  out["species"] = best.name;
  out["species_bare"] = best.bare;
  out["canopy_cover"] = std::round(vegetation::canopyCoverOf(catalog, k) * 1e4) / 1e4;
  out["species_candidates"] = nlohmann::json::array();
  out["species_candidates"].push_back(
      {{"name", best.name}, {"bare", best.bare}, {"probability", 1.0f - k.secondRatio}});
  if (k.second >= 0) {
    const auto& second = catalog.species[static_cast<size_t>(k.second)];
    out["species_candidates"].push_back({{"name", second.name}, {"bare", second.bare}, {"probability", k.secondRatio}});
  }
  return out;
}

// The landcover class at the point (datasets/landcover_classes.h): its code as stored, the
// scheme's name and coarse kind for it (null for a code the scheme does not know); null where the
// dataset has no landcover layer or no class there.
nlohmann::json landcoverJson(const std::optional<uint8_t>& code, const datasets::DatasetMeta& meta) {
  if (!code || !meta.landcover) return nullptr;
  const datasets::LandcoverClass* c = datasets::findLandcoverClass(*meta.landcover, *code);
  return {{"code", *code},
          {"name", c ? nlohmann::json(c->name) : nlohmann::json(nullptr)},
          {"kind", c ? nlohmann::json(datasets::toString(c->kind)) : nlohmann::json(nullptr)},
          {"scheme", datasets::toString(*meta.landcover)}};
}

}  // namespace

int runQuery(const QueryOptions& options, const Logger& log) {
  // The catalog first: a bad --species file is reported before any dataset I/O.
  const Result<vegetation::SpeciesCatalog> loaded = vegetation::loadSpeciesCatalogOrDefault(options.speciesFile);
  if (!loaded) return reportError(log, loaded.error());
  const vegetation::SpeciesCatalog* catalog = &*loaded;
  auto reader = datasets::DatasetReader::open(options.dataset);
  if (!reader) return reportError(log, reader.error());
  auto height = reader->heightAt(options.latDeg, options.lonDeg);
  if (!height) return reportError(log, height.error());
  if (std::isnan(*height)) {
    std::string m = "dataset ";
    m += options.dataset;
    m += " has no elevation data at lat ";
    m += std::to_string(options.latDeg);
    m += ", lon ";
    m += std::to_string(options.lonDeg);
    return reportError(log, makeError(ErrorKind::InvalidInput, m));
  }
  auto color = reader->colorAt(options.latDeg, options.lonDeg);
  if (!color) return reportError(log, color.error());
  auto ndvi = reader->ndviAt(options.latDeg, options.lonDeg);
  if (!ndvi) return reportError(log, ndvi.error());
  auto landcover = reader->landcoverAt(options.latDeg, options.lonDeg);
  if (!landcover) return reportError(log, landcover.error());
  auto canopy = reader->canopyAt(options.latDeg, options.lonDeg);
  if (!canopy) return reportError(log, canopy.error());

  nlohmann::json out = {
      {"dataset", reader->meta().name}, {"lat", options.latDeg}, {"lon", options.lonDeg}, {"height_m", *height}};
  if (*color) {
    const auto& c = **color;
    char hex[8];
    std::snprintf(hex, sizeof(hex), "#%02x%02x%02x", c[0], c[1], c[2]);
    out["color"] = {{"r", c[0]}, {"g", c[1]}, {"b", c[2]}, {"hex", hex}};
    vegetation::SpeciesMask allowed = vegetation::kAllSpecies;  // the class there narrows the choice
    if (*landcover && reader->meta().landcover)
      allowed = scene::landcoverMasks(*catalog, *reader->meta().landcover)[**landcover];
    out.update(speciesJson(scene::calibratedCatalog(*catalog, reader->meta()), c, ndvi->value_or(NAN), allowed));
  } else {
    out["color"] = nullptr;  // no imagery: no colour to choose a species from
    out["species"] = nullptr;
  }
  // Four decimals: the layer's step is 1/127, so more digits would only print the float.
  if (*ndvi)
    out["ndvi"] = std::round(static_cast<double>(**ndvi) * 1e4) / 1e4;
  else
    out["ndvi"] = nullptr;  // no NDVI layer (import --imagery-nir), or none at the point
  out["landcover"] = landcoverJson(*landcover, reader->meta());
  // The canopy height layer (import --canopy-height), to its 0.1 m step; null without the layer
  // or without a height at the point.
  out["canopy_height_m"] = *canopy ? nlohmann::json(std::round(static_cast<double>(**canopy) * 10.0) / 10.0)
                                   : nlohmann::json(nullptr);
  std::cout << out.dump(2) << "\n";
  return kExitOk;
}

}  // namespace vegstream::app
