#include "app/sample_dataset.h"

#include "datasets/geotiff_import.h"
#include "datasets/progress.h"

namespace vegstream::app {
namespace fs = std::filesystem;

Result<fs::path> ensureZionSample(const fs::path& samplesDir, const fs::path& datasetDir, const Logger& log) {
  std::error_code ec;
  if (fs::exists(datasetDir / "dataset.json", ec)) return datasetDir;
  const fs::path zion = samplesDir / "zion";
  if (!fs::exists(zion / "srtm.tif", ec))
    return makeError(
        ErrorKind::NotFound,
        (zion / "srtm.tif").string() + ": the Zion sample is missing; give a dataset directory (vegstream import)");
  log->info("importing the Zion sample once into {}", datasetDir.string());
  datasets::GeoTiffImportOptions o;
  o.dem = zion / "srtm.tif";
  o.imagery.bands = {zion / "landsat_b4.tif", zion / "landsat_b3.tif", zion / "landsat_b2.tif"};
  o.imagery.stretch = datasets::Stretch{};  // 1st–99th percentiles
  o.heightResampling = datasets::HeightResampling::Cubic;
  o.out = datasetDir;
  o.name = "zion";
  o.attribution = "SRTM (CGIAR-CSI v4.1), Landsat 8 (USGS), via spDataLarge (CC0)";
  datasets::ProgressReporter progress("import zion", stderr, 0);
  auto meta = datasets::importGeoTiff(o, log, progress);
  if (!meta) return meta.error();
  return datasetDir;
}

}  // namespace vegstream::app
