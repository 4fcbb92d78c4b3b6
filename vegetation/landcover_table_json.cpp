// The catalog's "landcover" table (landcover_species.h, landcover_table_json.h): kind → species
// names, checked against the catalog; every problem one line naming the field.
#include "vegetation/landcover_table_json.h"

#include "vegetation/species_catalog.h"

namespace vegstream::vegetation {

Result<LandcoverTable> readLandcoverTable(const nlohmann::json& value, const std::vector<Species>& species,
                                          const std::string& sourceName) {
  auto fail = [&](const std::string& path, const std::string& problem) -> Error {
    return makeError(ErrorKind::InvalidInput, sourceName + ": " + path + ": " + problem);
  };
  if (!value.is_object()) return fail("landcover", "must be an object of landcover kind → [species names]");
  LandcoverTable table = defaultLandcoverTable(species);
  for (auto it = value.begin(); it != value.end(); ++it) {
    const std::string path = "landcover." + it.key();
    int kind = -1;
    for (size_t k = 0; k < kLandcoverKindCount; ++k)
      if (it.key() == landcoverKindName(static_cast<LandcoverKind>(k))) kind = static_cast<int>(k);
    if (kind < 0)
      return fail(path, "unknown landcover kind (allowed here: tree, shrub, grass, crop, bare, built, water, snow, "
                        "wetland)");
    if (!it.value().is_array()) return fail(path, "must be an array of species names");
    SpeciesMask mask = 0;
    for (size_t j = 0; j < it.value().size(); ++j) {
      const std::string at = path + "[" + std::to_string(j) + "]";
      const nlohmann::json& name = it.value()[j];
      if (!name.is_string()) return fail(at, "must be a species name (a string)");
      int found = -1;
      for (size_t i = 0; i < species.size(); ++i)
        if (species[i].name == name.get<std::string>()) found = static_cast<int>(i);
      if (found < 0) return fail(at, "no species named \"" + name.get<std::string>() + "\" in the catalog");
      const SpeciesMask bit = SpeciesMask{1} << found;
      if (mask & bit) return fail(at, "\"" + name.get<std::string>() + "\" is named twice");
      mask |= bit;
    }
    table[static_cast<size_t>(kind)] = mask;
  }
  return table;
}

}  // namespace vegstream::vegetation
