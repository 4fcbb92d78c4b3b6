#pragma once
// The catalog's "landcover" object (landcover_species.h has its format), read for
// species_catalog.cpp. Private to vegetation/ (it sees nlohmann::json).

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/result.h"
#include "vegetation/landcover_species.h"

namespace vegstream::vegetation {

// The default table (defaultLandcoverTable(species)) with the kinds `value` names replaced.
// InvalidInput naming `sourceName` and the field: not an object, an unknown kind, not an array
// of strings, a name the catalog does not have, a name given twice for one kind.
Result<LandcoverTable> readLandcoverTable(const nlohmann::json& value, const std::vector<Species>& species,
                                          const std::string& sourceName);

}  // namespace vegstream::vegetation
