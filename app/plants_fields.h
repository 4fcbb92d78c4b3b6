#pragma once
// The printed digits of `vegstream plants` (app/plants_command.h), decided once for every
// format: JSON prints these strings as they are; the GIS exports (app/plants_export.h) write
// the doubles they read back as, so a GeoPackage, GeoJSON or CSV value equals the JSON's.
//
//   lat, lon        10 decimals (about 10 µm)       height_m        3 decimals (mm)
//   plant_height_m  4 decimals   stiffness 5   s_prime 5            (plants)
//   tree_height_m   3 decimals   crown_m   3   s_prime 5            (trees)

#include <string>

#include "scene/plants_in_box.h"
#include "scene/trees_in_box.h"

namespace vegstream::app {

struct PlantFields {
  std::string lat, lon, height, plantHeight, stiffness, sPrime;
};
PlantFields fieldsOf(const scene::BoxPlant& plant);

struct TreeFields {
  std::string lat, lon, height, treeHeight, crown, sPrime;
};
TreeFields fieldsOf(const scene::BoxTree& tree);

// printf-style formatting of one number ("%.10f").
std::string formatNumber(const char* format, double v);

}  // namespace vegstream::app
