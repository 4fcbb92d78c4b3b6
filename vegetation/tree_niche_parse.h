#pragma once
// The catalog's "niche" object of a tree species (format in tree_niche.h), for
// species_entry_parse.cpp.

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "vegetation/tree_types.h"

namespace vegstream::vegetation {

// Parses `v` into `out`. On a problem returns false with `field` the path below the niche
// (".slope_deg[1]", or "" for the object itself) and `problem` what is wrong.
bool parseTreeNiche(const nlohmann::json& v, TreeNiche& out, std::string& field, std::string& problem);

}  // namespace vegstream::vegetation
