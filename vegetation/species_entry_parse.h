#pragma once
// One entry of the species catalog's "species" array (format in species_catalog.h), for
// species_catalog.cpp: its name, colour score, plant shape, surface, density and horizon, and
// a tree species' "tree" object.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "vegetation/species_catalog.h"
#include "vegetation/species_json_parser.h"

namespace vegstream::vegetation::species_json {

// Parses obj (at `path`, "species[2]") into out; false with the problem recorded in ps.
bool parseSpecies(Parser& ps, const nlohmann::json& obj, const std::string& path, Species& out);

}  // namespace vegstream::vegetation::species_json
