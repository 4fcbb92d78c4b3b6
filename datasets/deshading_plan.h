#pragma once
// Which sun de-shades an import's imagery (deshading.h), and what dataset.json records of it:
//   1. the sun as stated (GeoTiffImportOptions::imagerySun)                 source "given";
//   2. the sun at the dataset's centre at --imagery-datetime (geo/solar_position.h, NOAA's
//      equations, refraction included)                                      "imagery datetime";
//   3. otherwise the sun estimated from the imagery and the DEM (sun_estimate.h) "estimated",
//      or no de-shading when the terrain cannot show it                     "none".
// Display-stretched imagery is never de-shaded (its bytes are not linear light), nor is any
// with --deshading off, nor imagery taken with the sun below the horizon: all "none", with the
// reason in the record's note.

#include <functional>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "core/log.h"
#include "core/result.h"
#include "datasets/dataset_format.h"
#include "datasets/geotiff_import.h"
#include "datasets/imagery_tiles.h"

namespace vegstream::datasets {

struct DeshadingPlan {
  std::optional<glm::dvec3> sun;  // ENU unit vector; nullopt: not de-shaded
  DeshadingRecord record;
};

// The datetime as the import states it: InvalidInput naming --imagery-datetime when it does not
// parse (geo::parseIsoDateTime's reason).
Result<int64_t> imageryUnixMs(const std::string& isoDatetime);

// tiling: the imagery as the tiles will sample it (its `sun` unset); centre: lon/lat of the
// dataset's centre; heightsOf / imageryOf: a max-zoom tile's heights and imagery (for the
// estimate).
Result<DeshadingPlan> planDeshading(const GeoTiffImportOptions& options, const RadiometryRecord& radiometry,
                                    const ImageryTiling& tiling, const std::vector<geo::TileId>& tiles,
                                    glm::dvec2 centreLonLat,
                                    const std::function<std::vector<float>(const geo::TileId&)>& heightsOf,
                                    const std::function<std::optional<TileImagery>(const geo::TileId&)>& imageryOf,
                                    const Logger& log);

}  // namespace vegstream::datasets
