#pragma once
// Loads the demo's terrain: a DEM GeoTIFF (or a directory holding srtm.tif, like the Zion
// sample) into a terrain::HeightGrid. Until the dataset importer exists (issue 3) only DEMs in
// geographic coordinates (EPSG:4326 / 4269) are accepted; anything else is refused clearly.

#include <filesystem>

#include "core/result.h"
#include "terrain/height_grid.h"

namespace vegstream::app {

Result<terrain::HeightGrid> loadDemGrid(const std::filesystem::path& datasetOrFile);

}  // namespace vegstream::app
