#include "app/dem_loader.h"

#include <cmath>
#include <limits>

#include "datasets/geotiff_reader.h"

namespace vegstream::app {
namespace fs = std::filesystem;

Result<terrain::HeightGrid> loadDemGrid(const fs::path& datasetOrFile) {
  std::error_code ec;
  if (!fs::exists(datasetOrFile, ec))
    return makeError(ErrorKind::NotFound, datasetOrFile.string() + ": no such file or directory");
  fs::path file = datasetOrFile;
  if (fs::is_directory(datasetOrFile, ec)) {
    file = datasetOrFile / "srtm.tif";
    if (!fs::exists(file, ec))
      return makeError(ErrorKind::InvalidInput, datasetOrFile.string() +
                                                    " holds no srtm.tif; give a DEM GeoTIFF or a directory with srtm.tif");
  }
  auto raster = datasets::readGeoTiff(file);
  if (!raster) return raster.error();
  const datasets::Raster& r = *raster;
  const auto& g = r.georef;
  if (g.epsg != 4326 && g.epsg != 4269)
    return makeError(ErrorKind::Unsupported,
                     file.string() + ": the demo reads DEMs in EPSG:4326 only (this one is " +
                         (g.epsg ? "EPSG:" + std::to_string(g.epsg) : g.crsDescription) +
                         "); other CRSs come through `vegstream import`");
  if (g.transform[2] != 0.0 || g.transform[4] != 0.0)
    return makeError(ErrorKind::Unsupported, file.string() + ": rotated rasters are not supported");

  terrain::HeightGrid grid;
  grid.width = r.width;
  grid.height = r.height;
  const auto first = g.pixelCentre(0, 0);
  grid.lonFirst = first[0];
  grid.latFirst = first[1];
  grid.lonStep = g.transform[1];
  grid.latStep = g.transform[5];
  grid.heights.resize(static_cast<size_t>(r.width) * static_cast<size_t>(r.height));
  size_t valid = 0;
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      const float v = r.at(col, row, 0);
      const bool ok = !r.isNodata(v) && v > -11000.0f && v < 9000.0f;  // physically possible heights
      grid.heights[static_cast<size_t>(row) * static_cast<size_t>(r.width) + static_cast<size_t>(col)] =
          ok ? v : std::numeric_limits<float>::quiet_NaN();
      valid += ok ? 1 : 0;
    }
  if (valid == 0) return makeError(ErrorKind::InvalidInput, file.string() + ": every height is nodata");
  return grid;
}

}  // namespace vegstream::app
