// `vegstream plants --format json` (plants_json.h).

#include "app/plants_json.h"

#include <nlohmann/json.hpp>

#include "app/plants_fields.h"

namespace vegstream::app {

void writePlantsJson(std::ostream& out, const std::vector<scene::BoxPlant>& rows,
                     const std::vector<scene::BoxTree>& trees, const vegetation::SpeciesCatalog& catalog,
                     const std::string& dataset, const std::string& bboxText, int seedLevel, int clusterSize) {
  // Written by hand, one plant per line: nlohmann would print the doubles with 17 digits.
  std::vector<std::string> names;
  for (const vegetation::Species& s : catalog.species) names.push_back(nlohmann::json(s.name).dump());
  out << "{\"dataset\": " << nlohmann::json(dataset).dump() << ",\n \"bbox\": [" << bboxText
      << "],\n \"seed_level\": " << seedLevel << ",\n \"cluster_size\": " << clusterSize
      << ",\n \"plant_count\": " << rows.size() << ",\n \"plants\": [";
  for (size_t i = 0; i < rows.size(); ++i) {
    const PlantFields f = fieldsOf(rows[i]);
    out << (i ? ",\n  " : "\n  ") << "{\"lat\": " << f.lat << ", \"lon\": " << f.lon << ", \"height_m\": " << f.height
        << ", \"species\": " << names[rows[i].species] << ", \"plant_height_m\": " << f.plantHeight
        << ", \"stiffness\": " << f.stiffness << ", \"s_prime\": " << f.sPrime << "}";
  }
  out << (rows.empty() ? "]" : "\n ]") << ",\n \"tree_count\": " << trees.size() << ",\n \"trees\": [";
  for (size_t i = 0; i < trees.size(); ++i) {
    const TreeFields f = fieldsOf(trees[i]);
    out << (i ? ",\n  " : "\n  ") << "{\"lat\": " << f.lat << ", \"lon\": " << f.lon << ", \"height_m\": " << f.height
        << ", \"species\": " << names[trees[i].species] << ", \"tree_height_m\": " << f.treeHeight
        << ", \"crown_m\": " << f.crown << ", \"s_prime\": " << f.sPrime << "}";
  }
  out << (trees.empty() ? "]}\n" : "\n ]}\n");
}

}  // namespace vegstream::app
