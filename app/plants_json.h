#pragma once
// `vegstream plants --format json` (app/plants_command.h): both tables in one document,
// {"dataset", "bbox", "seed_level", "cluster_size", "plant_count", "plants": [{…}, …],
// "tree_count", "trees": [{…}, …]}, one plant or tree per line, the digits of
// app/plants_fields.h. A plant: {"lat", "lon", "height_m", "species", "plant_height_m",
// "stiffness", "s_prime"}; a tree: {"lat", "lon", "height_m", "species", "tree_height_m",
// "crown_m", "s_prime"}.

#include <ostream>
#include <string>
#include <vector>

#include "scene/plants_in_box.h"
#include "scene/trees_in_box.h"
#include "vegetation/species_catalog.h"

namespace vegstream::app {

// bboxText: the box as it is echoed ("lon0, lat0, lon1, lat1").
void writePlantsJson(std::ostream& out, const std::vector<scene::BoxPlant>& plants,
                     const std::vector<scene::BoxTree>& trees, const vegetation::SpeciesCatalog& catalog,
                     const std::string& dataset, const std::string& bboxText, int seedLevel, int clusterSize);

}  // namespace vegstream::app
